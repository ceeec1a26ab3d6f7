#include "registry/scene_file.h"

#include <fmt/format.h>
#include <toml++/toml.h>

#include <filesystem>
#include <sstream>

#include "engine/core/error.h"
#include "engine/util/bounded_file.h"
#include "registry/scene_catalog.h"

namespace masav::scene {
namespace {

std::string where(std::string_view source, const toml::source_region& r) {
  if (r.begin.line == 0) return std::string(source);
  return fmt::format("{}:{}", source, r.begin.line);
}

// A TOML value as a ParamValue, or nullopt for arrays, tables, dates.
std::optional<ParamValue> to_value(const toml::node& n) {
  if (const auto* b = n.as_boolean()) return ParamValue(b->get());
  if (const auto* i = n.as_integer()) return ParamValue(int64_t(i->get()));
  if (const auto* f = n.as_floating_point()) return ParamValue(f->get());
  if (const auto* s = n.as_string()) return ParamValue(s->get());
  return std::nullopt;
}

// A value as TOML writes it (arrays, tables and dates included), for error messages.
std::string shown(const toml::node& n) {
  std::ostringstream ss;
  n.visit([&](auto&& v) { ss << v; });
  return ss.str();
}

// Rethrows a validation error with the file and line in front.
[[noreturn]] void rethrow_at(const Error& e, const std::string& at) {
  throw Error("", at, e.problem(), e.remedy());
}

}  // namespace

SceneFile parse_scene(std::string_view text, std::string_view source) {
  toml::table root;
  try {
    root = toml::parse(text, source);
  } catch (const toml::parse_error& e) {
    const auto& b = e.source().begin;
    throw Error("", fmt::format("{}:{}:{}", source, b.line, b.column),
                fmt::format("malformed TOML: {}", e.description()),
                "fix the syntax (TOML: [table] headers, key = value lines, strings in quotes)");
  }

  // The type decides which tables are allowed.
  std::string type = "particles";
  if (const toml::node* s = root.get("scene")) {
    if (!s->is_table())
      throw Error("", where(source, s->source()), "'scene' must be a table ([scene])",
                  "write the scene's type under a [scene] header");
    if (const toml::node* t = s->as_table()->get("type")) {
      if (!t->is_string())
        throw_invalid(where(source, t->source()), "scene.type", shown(*t),
                      "a string naming the scene type");
      type = t->as_string()->get();
    }
  }
  SceneFile f;
  f.source = std::string(source);
  try {
    f.params = default_params(find_scene_type(type));
  } catch (const Error& e) {
    rethrow_at(e, std::string(source));
  }
  f.type = type;

  for (const auto& [table_key, table_node] : root) {
    const std::string table(table_key.str());
    const std::string at = where(source, table_node.source());
    if (!f.params.has_table(table)) {
      std::string names;
      for (const auto* t : f.params.tables()) names += (names.empty() ? "" : ", ") + t->name();
      throw_invalid(at, "table", table,
                    fmt::format("one of the tables of a '{}' scene: {}", type, names));
    }
    const toml::table* entries = table_node.as_table();
    if (!entries)
      throw Error("", at, fmt::format("'{}' must be a table ([{}])", table, table),
                  fmt::format("put its keys under a [{}] header", table));
    for (const auto& [key_name, value] : *entries) {
      const std::string path = table + "." + std::string(key_name.str());
      const std::string vat = where(source, value.source());
      try {
        const ParamSpec& spec = f.params.spec(path);
        const auto v = to_value(value);
        if (!v) throw_invalid("scene", path, shown(value), spec.allowed());
        f.params.set(path, *v);
      } catch (const Error& e) {
        rethrow_at(e, vat);
      }
    }
  }
  return f;
}

SceneFile load_scene_file(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec))
    throw Error("", "scene file", fmt::format("'{}' does not exist", path),
                "give the path of a scene file (scenes/ holds the shipped ones; `masav schema` "
                "prints a template)");
  if (std::filesystem::is_directory(path, ec))
    throw Error("", "scene file", fmt::format("'{}' is a directory", path),
                "give the path of a .toml scene file");
  // Bounded: a device or FIFO (which never ends) is refused, and so is a file over 16 MiB.
  const std::string text = read_bounded_file(path, "scene file");
  if (text.find('\0') != std::string::npos)
    throw Error("", "scene file", fmt::format("'{}' is not a text file", path),
                "give the path of a .toml scene file");
  return parse_scene(text, path);
}

SceneFile default_scene(std::string_view type) {
  SceneFile f;
  f.source = "<defaults>";
  f.type = std::string(type);
  f.params = default_params(find_scene_type(type));
  return f;
}

namespace {

// A value as TOML: strings through toml++'s serializer, which escapes quotes, backslashes and
// control characters (a scene file masav writes always reads back); numbers and flags as the
// schema formats them.
std::string toml_value(const ParamValue& v) {
  if (const auto* text = std::get_if<std::string>(&v)) {
    // A basic "..." string, escaped where needed (UTF-8 text kept as it is).
    std::ostringstream out;
    out << toml::toml_formatter{toml::value<std::string>(*text),
                                toml::format_flags::allow_unicode_strings};
    return out.str();
  }
  return format_value(v);
}

// A comment's text on one line: a help string never breaks the file.
std::string one_line(std::string text) {
  for (char& c : text)
    if (c == '\n' || c == '\r') c = ' ';
  return text;
}

}  // namespace

std::string scene_to_toml(const ParamSet& params, bool with_help) {
  std::string out;
  for (const TableSchema* t : params.tables()) {
    if (with_help) out += fmt::format("# {}\n", one_line(t->help()));
    out += fmt::format("[{}]\n", t->name());
    for (const ParamSpec& p : t->params()) {
      const std::string path = t->name() + "." + p.key;
      if (with_help)
        out += fmt::format("# {} ({}; default {})\n", one_line(p.help), one_line(p.allowed()),
                           one_line(format_value(p.def)));
      out += fmt::format("{} = {}\n", p.key, toml_value(params.get(path)));
    }
    out += "\n";
  }
  return out;
}

}  // namespace masav::scene
