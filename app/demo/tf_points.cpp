#include "app/demo/tf_points.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "engine/core/error.h"
#include "engine/util/output_file.h"
#include "engine/volume/volume_render.h"

namespace masav::app {

std::optional<size_t> add_tf_point(std::vector<TransferPoint>& pts, double value) {
  value = std::clamp(value, 0.0, 1.0);
  if (tf_point_near(pts, value, kMinTfGap)) return std::nullopt;
  TransferPoint p{value, 0, 0, 0, 0};
  if (pts.empty()) {
    pts.push_back(p);
    return 0;
  }
  // The function's colour at `value`: linear between the neighbours, constant beyond the ends
  // (as resample_transfer interpolates).
  const auto after = std::upper_bound(pts.begin(), pts.end(), value,
                                      [](double v, const TransferPoint& q) { return v < q.value; });
  if (after == pts.begin()) {
    p = *after;
  } else if (after == pts.end()) {
    p = pts.back();
  } else {
    const TransferPoint& a = *(after - 1);
    const TransferPoint& b = *after;
    const double w = (value - a.value) / (b.value - a.value);
    p = {0, a.r + (b.r - a.r) * w, a.g + (b.g - a.g) * w, a.b + (b.b - a.b) * w,
         a.a + (b.a - a.a) * w};
  }
  p.value = value;
  const size_t index = size_t(after - pts.begin());
  pts.insert(after, p);
  return index;
}

void move_tf_point(std::vector<TransferPoint>& pts, size_t i, double value, double opacity) {
  if (i >= pts.size()) return;
  const double lo = i == 0 ? 0.0 : pts[i - 1].value + kMinTfGap;
  const double hi = i + 1 == pts.size() ? 1.0 : pts[i + 1].value - kMinTfGap;
  // Points read from a file may sit closer than kMinTfGap: such a point keeps its value.
  if (lo <= hi) pts[i].value = std::clamp(value, lo, hi);
  pts[i].a = std::clamp(opacity, 0.0, 1.0);
}

void set_tf_colour(std::vector<TransferPoint>& pts, size_t i, double r, double g, double b,
                   double a) {
  if (i >= pts.size()) return;
  pts[i].r = std::clamp(r, 0.0, 1.0);
  pts[i].g = std::clamp(g, 0.0, 1.0);
  pts[i].b = std::clamp(b, 0.0, 1.0);
  pts[i].a = std::clamp(a, 0.0, 1.0);
}

bool delete_tf_point(std::vector<TransferPoint>& pts, size_t i) {
  if (i >= pts.size() || pts.size() <= kMinTfPoints) return false;
  pts.erase(pts.begin() + std::ptrdiff_t(i));
  return true;
}

std::optional<size_t> tf_point_near(const std::vector<TransferPoint>& pts, double value,
                                    double tolerance) {
  std::optional<size_t> best;
  for (size_t i = 0; i < pts.size(); ++i) {
    const double d = std::abs(pts[i].value - value);
    if (d < tolerance && (!best || d < std::abs(pts[*best].value - value))) best = i;
  }
  return best;
}

void put_tf_point(std::vector<TransferPoint>& pts, const std::vector<std::string>& numbers,
                  const std::string& where) {
  static const char* fields[] = {"value", "r", "g", "b", "a"};
  if (numbers.size() != 5)
    throw_invalid(where, "tf point", std::to_string(numbers.size()) + " numbers",
                  "five numbers: value r g b a");
  double v[5];
  for (size_t k = 0; k < 5; ++k) {
    char* end = nullptr;
    v[k] = std::strtod(numbers[k].c_str(), &end);
    if (end == numbers[k].c_str() || *end != '\0' || !std::isfinite(v[k]) || v[k] < 0 || v[k] > 1)
      throw_invalid(where, fmt::format("tf point field {}", fields[k]), numbers[k],
                    "a number in [0, 1]");
  }
  std::optional<size_t> i = tf_point_near(pts, v[0], kMinTfGap);
  if (!i) i = add_tf_point(pts, v[0]);
  set_tf_colour(pts, *i, v[1], v[2], v[3], v[4]);
}

std::optional<std::string> transfer_table(const scene::ParamSet& p) {
  for (const char* table : {"volume", "raymarch"})
    if (p.has(std::string(table) + ".transfer")) return std::string(table);
  return std::nullopt;
}

void sync_tf_editor(TfEditorState& e, const scene::ParamSet& p, const std::string& table) {
  const std::string keys =
      table + "\n" + p.get_text(table + ".transfer") + "\n" + p.get_text(table + ".transfer_file");
  if (keys == e.keys && !e.points.empty()) return;
  e.keys = keys;
  try {
    e.points = volume::transfer_points_of(p, table);
  } catch (const Error& err) {
    e.points = volume::default_transfer_points();
    e.message = err.what();
    e.message_is_error = true;
  }
  if (e.selected && *e.selected >= e.points.size()) e.selected.reset();
  if (e.dragging && *e.dragging >= e.points.size()) e.dragging.reset();
}

void apply_tf_points(scene::SceneInstance& s, const std::string& table,
                     const std::vector<TransferPoint>& pts) {
  const std::string text = volume::format_inline_transfer(pts);
  (void)volume::parse_inline_transfer(text, table + ".transfer");  // refused before any change
  s.set(table + ".transfer_file", std::string());
  s.set(table + ".transfer", text);
}

void reset_tf_points(scene::SceneInstance& s, const std::string& table) {
  s.set(table + ".transfer", std::string());
  s.set(table + ".transfer_file", std::string());
}

namespace {

void report(TfEditorState& e, std::string text, bool error) {
  e.message = std::move(text);
  e.message_is_error = error;
}

}  // namespace

void save_tf_file(TfEditorState& e, const std::string& path) {
  const std::filesystem::path parent = std::filesystem::path(path).parent_path();
  std::error_code ec;
  if (!parent.empty() && !std::filesystem::is_directory(parent, ec)) {
    report(e, fmt::format("Save TF: cannot write {}: the folder does not exist", path), true);
    return;
  }
  try {
    write_output(path, volume::format_transfer_file(e.points), "Save TF");
  } catch (const Error& err) {
    report(e, fmt::format("Save TF: cannot write {}: {}", path, err.problem()), true);
    return;
  }
  report(e, fmt::format("saved {} points to {}", e.points.size(), path), false);
}

void load_tf_file(TfEditorState& e, scene::SceneInstance& s, const std::string& table,
                  const std::string& path) {
  try {
    const std::vector<TransferPoint> pts = volume::load_transfer_points(path);
    apply_tf_points(s, table, pts);
    e.points = pts;
    e.keys.clear();
    e.selected.reset();
    report(e, fmt::format("loaded {} points from {}", pts.size(), path), false);
  } catch (const Error& err) {
    report(e, err.what(), true);
  }
}

void forget_tf_scene(TfEditorState& e) {
  std::string path = std::move(e.path);
  e = TfEditorState{};
  e.path = std::move(path);
}

void check_tf_words(const std::vector<std::string>& words, const std::string& where) {
  const std::string forms = "load FILE, save FILE, reset, point V R G B A or delete V";
  if (words.empty()) throw_invalid(where, "tf", "nothing", forms);
  const std::string& verb = words[0];
  const size_t args = words.size() - 1;
  const bool ok = ((verb == "load" || verb == "save" || verb == "delete") && args == 1) ||
                  (verb == "reset" && args == 0) || (verb == "point" && args == 5);
  if (!ok) throw_invalid(where, "tf", verb + fmt::format(" with {} arguments", args), forms);
  if (verb == "point") {
    std::vector<TransferPoint> scratch = volume::default_transfer_points();
    put_tf_point(scratch, {words.begin() + 1, words.end()}, where);
  }
  if (verb == "delete") {
    char* end = nullptr;
    const double v = std::strtod(words[1].c_str(), &end);
    if (end == words[1].c_str() || *end != '\0' || !(v >= 0 && v <= 1))
      throw_invalid(where, "tf delete", words[1], "the value of a point, in [0, 1]");
  }
}

std::string run_tf_words(TfEditorState& e, scene::SceneInstance& s,
                         const std::vector<std::string>& words, const std::string& where) {
  check_tf_words(words, where);
  const std::optional<std::string> table = transfer_table(s.params());
  if (!table)
    throw Error("", where, "tf: this scene has no transfer function",
                "switch to an atom-volume scene or open a volume file first");
  sync_tf_editor(e, s.params(), *table);
  const std::string& verb = words[0];
  if (verb == "load") load_tf_file(e, s, *table, words[1]);
  if (verb == "save") save_tf_file(e, words[1]);
  if (verb == "reset") {
    reset_tf_points(s, *table);
    report(e, "the default transfer function", false);
  }
  if (verb == "point" || verb == "delete") {
    std::vector<TransferPoint> pts = e.points;
    if (verb == "point") {
      put_tf_point(pts, {words.begin() + 1, words.end()}, where);
    } else {
      const std::optional<size_t> i =
          tf_point_near(pts, std::strtod(words[1].c_str(), nullptr), kMinTfGap);
      if (!i) throw_invalid(where, "tf delete", words[1], "the value of one of the points");
      if (!delete_tf_point(pts, *i))
        throw Error("", where,
                    fmt::format("tf delete {}: only {} points left", words[1], pts.size()),
                    fmt::format("a transfer function keeps at least {} points", kMinTfPoints));
    }
    apply_tf_points(s, *table, pts);
    report(e, fmt::format("{} points", pts.size()), false);
  }
  e.keys.clear();
  sync_tf_editor(e, s.params(), *table);
  return e.message;
}

}  // namespace masav::app
