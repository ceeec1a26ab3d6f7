#include "engine/volume/transfer_function.h"

#include <fmt/format.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "engine/core/error.h"
#include "engine/util/bounded_file.h"

namespace masav::volume {

std::vector<TransferPoint> default_transfer_points() {
  return {{0.00, 0.0, 0.0, 1.0, 0.00},
          {0.05, 0.0, 0.1, 1.0, 0.01},
          {0.35, 0.0, 1.0, 0.2, 0.06},
          {0.70, 1.0, 0.9, 0.0, 0.16},
          {1.00, 1.0, 0.0, 0.0, 0.30}};
}

namespace {

// Entries separated by `separator` (a file's lines, or an inline key's ';'), each "value r g b
// a"; errors name `where`, the entry as "`unit` N" and the field, and `subject` when there is
// no entry at all.
std::vector<TransferPoint> parse_points(const std::string& text, const std::string& where,
                                        char separator, const std::string& unit,
                                        const std::string& subject) {
  std::vector<TransferPoint> pts;
  std::istringstream in(text);
  std::string line;
  int number = 0;
  static const char* fields[] = {"value", "r", "g", "b", "a"};
  while (std::getline(in, line, separator)) {
    ++number;
    if (const auto hash = line.find('#'); hash != std::string::npos) line.erase(hash);
    std::istringstream ls(line);
    double v[5];
    int got = 0;
    std::string token;
    const std::string entry = fmt::format("{} {}", unit, number);
    while (ls >> token) {
      if (got == 5) throw_invalid(where, entry, line, "five numbers: value r g b a");
      char* end = nullptr;
      v[got] = std::strtod(token.c_str(), &end);
      if (end == token.c_str() || *end != '\0' || !std::isfinite(v[got]) || v[got] < 0 ||
          v[got] > 1)
        throw_invalid(where, fmt::format("{} field {}", entry, fields[got]), token,
                      "a number in [0, 1]");
      ++got;
    }
    if (got == 0) continue;
    if (got != 5) throw_invalid(where, entry, line, "five numbers: value r g b a");
    if (!pts.empty() && !(v[0] > pts.back().value))
      throw_invalid(where, entry + " field value", fmt::format("{}", v[0]),
                    fmt::format("greater than the previous value {}", pts.back().value));
    pts.push_back({v[0], v[1], v[2], v[3], v[4]});
  }
  if (pts.empty())
    throw_invalid(where, subject, "no entries",
                  "at least one entry \"value r g b a\" (numbers in [0, 1])");
  return pts;
}

std::string format_point(const TransferPoint& p) {
  // {} is the shortest text that reads back as the same double: a save and a load round-trip.
  return fmt::format("{} {} {} {} {}", p.value, p.r, p.g, p.b, p.a);
}

}  // namespace

std::vector<TransferPoint> parse_transfer_points(const std::string& text,
                                                 const std::string& where) {
  return parse_points(text, where, '\n', "line", "transfer function");
}

std::vector<TransferPoint> parse_inline_transfer(const std::string& text, const std::string& key) {
  return parse_points(text, "scene", ';', key + " point", key);
}

std::string format_inline_transfer(const std::vector<TransferPoint>& points) {
  std::string out;
  for (const TransferPoint& p : points) out += (out.empty() ? "" : "; ") + format_point(p);
  return out;
}

std::string format_transfer_file(const std::vector<TransferPoint>& points) {
  std::string out = "# value r g b a (each in [0, 1], values ascending)\n";
  for (const TransferPoint& p : points) out += format_point(p) + "\n";
  return out;
}

std::vector<TransferPoint> load_transfer_points(const std::string& path) {
  return parse_transfer_points(read_bounded_file(path, "transfer function"), path);
}

std::vector<Vec4d> resample_transfer(const std::vector<TransferPoint>& pts, uint32_t size) {
  if (pts.empty())
    throw_invalid("transfer function", "points", "none", "at least one control point");
  if (size < 2) throw_invalid("transfer function", "size", std::to_string(size), "at least 2");
  std::vector<Vec4d> out(size);
  size_t j = 0;
  for (uint32_t k = 0; k < size; ++k) {
    const double v = double(k) / (size - 1);
    while (j + 1 < pts.size() && pts[j + 1].value <= v) ++j;
    const TransferPoint& a = pts[j];
    if (v <= a.value || j + 1 == pts.size()) {
      out[k] = {a.r, a.g, a.b, a.a};
      continue;
    }
    const TransferPoint& b = pts[j + 1];
    const double w = (v - a.value) / (b.value - a.value);
    out[k] = {a.r + (b.r - a.r) * w, a.g + (b.g - a.g) * w, a.b + (b.b - a.b) * w,
              a.a + (b.a - a.a) * w};
  }
  return out;
}

}  // namespace masav::volume
