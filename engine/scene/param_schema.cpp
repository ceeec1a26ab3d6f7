#include "engine/scene/param_schema.h"

#include <fmt/format.h>

#include <charconv>
#include <cmath>

#include "engine/core/enum_names.h"
#include "engine/core/error.h"

namespace masav::scene {
namespace {

std::string join(const std::vector<std::string>& v) {
  std::string out;
  for (const auto& s : v) out += (out.empty() ? "" : ", ") + s;
  return out;
}

// Shortest round-trip form, always with a decimal point so TOML reads it back as a float.
std::string number(double v) {
  std::string s = fmt::format("{}", v);
  if (s.find_first_of(".eEn") == std::string::npos) s += ".0";
  return s;
}

}  // namespace

const char* param_type_name(ParamType t) {
  static const char* const names[] = {"boolean", "integer", "number", "choice", "string"};
  return enum_name(t, names);
}

std::string format_value(const ParamValue& v) {
  struct {
    std::string operator()(bool b) const { return b ? "true" : "false"; }
    std::string operator()(int64_t i) const { return std::to_string(i); }
    std::string operator()(double d) const { return number(d); }
    std::string operator()(const std::string& s) const { return fmt::format("\"{}\"", s); }
  } f;
  return std::visit(f, v);
}

std::string ParamSpec::allowed() const {
  const std::string u = unit.empty() ? "" : " " + unit;
  switch (type) {
    case ParamType::flag:
      return "true or false";
    case ParamType::integer:
      return fmt::format("an integer in [{}, {}]{}", int_min, int_max, u);
    case ParamType::real:
      return fmt::format("a number in [{}, {}]{}", number(real_min), number(real_max), u);
    case ParamType::choice:
      return "one of " + join(choices);
    case ParamType::text:
      return "a string";
  }
  return "?";
}

ParamValue ParamSpec::validate(std::string_view path, const ParamValue& v) const {
  auto bad = [&]() -> ParamValue { throw_invalid("scene", path, format_value(v), allowed()); };
  switch (type) {
    case ParamType::flag:
      if (!std::holds_alternative<bool>(v)) bad();
      return v;
    case ParamType::integer: {
      int64_t i = 0;
      if (const auto* p = std::get_if<int64_t>(&v))
        i = *p;
      else if (const auto* d = std::get_if<double>(&v);
               d && std::isfinite(*d) && *d == std::floor(*d) && std::abs(*d) < 9.0e15)
        i = int64_t(*d);
      else
        bad();
      if (i < int_min || i > int_max) bad();
      return i;
    }
    case ParamType::real: {
      double d = 0;
      if (const auto* p = std::get_if<double>(&v))
        d = *p;
      else if (const auto* i = std::get_if<int64_t>(&v))
        d = double(*i);
      else
        bad();
      if (!std::isfinite(d) || d < real_min || d > real_max) bad();
      return d;
    }
    case ParamType::choice: {
      const auto* s = std::get_if<std::string>(&v);
      if (!s) bad();
      for (const auto& c : choices)
        if (c == *s) return v;
      return bad();
    }
    case ParamType::text:
      if (!std::holds_alternative<std::string>(v)) bad();
      return v;
  }
  return bad();
}

TableSchema::TableSchema(std::string name, std::string help)
    : name_(std::move(name)), help_(std::move(help)) {}

ParamSpec& TableSchema::add(std::string key, ParamType type, std::string help) {
  if (find(key))
    throw Error("", "scene schema", fmt::format("[{}] declares '{}' twice", name_, key),
                "internal error: each parameter is declared once");
  ParamSpec& p = params_.emplace_back();
  p.key = std::move(key);
  p.type = type;
  p.help = std::move(help);
  return p;
}

TableSchema& TableSchema::flag(std::string key, bool def, std::string help) {
  add(std::move(key), ParamType::flag, std::move(help)).def = def;
  return *this;
}
TableSchema& TableSchema::integer(std::string key, int64_t def, int64_t lo, int64_t hi,
                                  std::string help, std::string unit) {
  ParamSpec& p = add(std::move(key), ParamType::integer, std::move(help));
  p.def = def, p.int_min = lo, p.int_max = hi, p.unit = std::move(unit);
  return *this;
}
TableSchema& TableSchema::real(std::string key, double def, double lo, double hi, std::string help,
                               std::string unit) {
  ParamSpec& p = add(std::move(key), ParamType::real, std::move(help));
  p.def = def, p.real_min = lo, p.real_max = hi, p.unit = std::move(unit);
  return *this;
}
TableSchema& TableSchema::choice(std::string key, std::string def, std::vector<std::string> choices,
                                 std::string help) {
  ParamSpec& p = add(std::move(key), ParamType::choice, std::move(help));
  p.def = std::move(def), p.choices = std::move(choices);
  return *this;
}
TableSchema& TableSchema::text(std::string key, std::string def, std::string help) {
  add(std::move(key), ParamType::text, std::move(help)).def = std::move(def);
  return *this;
}
TableSchema& TableSchema::steps(double step) {
  params_.back().step = step;
  return *this;
}
TableSchema& TableSchema::log_scale() {
  params_.back().logarithmic = true;
  return *this;
}

const ParamSpec* TableSchema::find(std::string_view key) const {
  for (const auto& p : params_)
    if (p.key == key) return &p;
  return nullptr;
}

std::string TableSchema::keys() const {
  std::vector<std::string> k;
  for (const auto& p : params_) k.push_back(p.key);
  return join(k);
}

void ParamSet::add_table(const TableSchema& t) {
  if (has_table(t.name())) return;
  tables_.push_back(&t);
  for (const auto& p : t.params()) {
    // Defaults pass their own validation: a schema with a bad default is a programming error.
    const std::string path = t.name() + "." + p.key;
    values_[path] = Entry{&p, p.validate(path, p.def), 0};
  }
}

bool ParamSet::has_table(std::string_view name) const {
  for (const auto* t : tables_)
    if (t->name() == name) return true;
  return false;
}

const ParamSet::Entry& ParamSet::entry(std::string_view path) const {
  auto it = values_.find(path);
  if (it != values_.end()) return it->second;
  const auto dot = path.find('.');
  const std::string_view table = dot == std::string_view::npos ? path : path.substr(0, dot);
  for (const auto* t : tables_)
    if (t->name() == table)
      throw_invalid("scene", "key", std::string(path),
                    fmt::format("a key of [{}]: {}", t->name(), t->keys()));
  std::vector<std::string> names;
  for (const auto* t : tables_) names.push_back(t->name());
  throw_invalid("scene", "table", std::string(table), "one of " + join(names));
}
ParamSet::Entry& ParamSet::entry(std::string_view path) {
  return const_cast<Entry&>(static_cast<const ParamSet*>(this)->entry(path));
}

const ParamSpec& ParamSet::spec(std::string_view path) const {
  return *entry(path).spec;
}
const ParamValue& ParamSet::get(std::string_view path) const {
  return entry(path).value;
}
bool ParamSet::get_flag(std::string_view path) const {
  return std::get<bool>(get(path));
}
int64_t ParamSet::get_int(std::string_view path) const {
  return std::get<int64_t>(get(path));
}
double ParamSet::get_real(std::string_view path) const {
  return std::get<double>(get(path));
}
const std::string& ParamSet::get_text(std::string_view path) const {
  return std::get<std::string>(get(path));
}
uint64_t ParamSet::version(std::string_view path) const {
  return entry(path).version;
}

bool ParamSet::set(std::string_view path, const ParamValue& v) {
  Entry& e = entry(path);
  ParamValue checked = e.spec->validate(path, v);
  if (checked == e.value) return false;
  e.value = std::move(checked);
  e.version = ++clock_;
  return true;
}

bool ParamSet::set_from_string(std::string_view path, std::string_view text) {
  const ParamSpec& s = spec(path);
  auto bad = [&] { throw_invalid("scene", path, std::string(text), s.allowed()); };
  switch (s.type) {
    case ParamType::flag:
      if (text == "true" || text == "1" || text == "on") return set(path, true);
      if (text == "false" || text == "0" || text == "off") return set(path, false);
      bad();
      break;
    case ParamType::integer: {
      int64_t i = 0;
      const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), i);
      if (ec != std::errc() || ptr != text.data() + text.size()) bad();
      return set(path, i);
    }
    case ParamType::real: {
      // std::from_chars for double is in GCC 11+, but strtod also takes "5e4" and "inf".
      const std::string t(text);
      char* end = nullptr;
      const double d = std::strtod(t.c_str(), &end);
      if (t.empty() || end != t.c_str() + t.size()) bad();
      return set(path, d);
    }
    case ParamType::choice:
    case ParamType::text: {
      std::string t(text);
      if (t.size() >= 2 && t.front() == '"' && t.back() == '"') t = t.substr(1, t.size() - 2);
      return set(path, t);
    }
  }
  return false;
}

std::vector<std::string> ParamSet::changed_since(uint64_t version) const {
  std::vector<std::string> out;
  for (const auto& [path, e] : values_)
    if (e.version > version) out.push_back(path);
  return out;
}

}  // namespace masav::scene
