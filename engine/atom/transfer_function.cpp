#include "engine/atom/transfer_function.h"

#include <fmt/format.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "engine/core/error.h"
#include "engine/util/bounded_file.h"

namespace masav::atom {

std::vector<TransferPoint> default_transfer_points() {
  return {{0.00, 0.0, 0.0, 1.0, 0.00},
          {0.05, 0.0, 0.1, 1.0, 0.01},
          {0.35, 0.0, 1.0, 0.2, 0.06},
          {0.70, 1.0, 0.9, 0.0, 0.16},
          {1.00, 1.0, 0.0, 0.0, 0.30}};
}

std::vector<TransferPoint> parse_transfer_points(const std::string& text,
                                                 const std::string& where) {
  std::vector<TransferPoint> pts;
  std::istringstream in(text);
  std::string line;
  int number = 0;
  static const char* fields[] = {"value", "r", "g", "b", "a"};
  while (std::getline(in, line)) {
    ++number;
    if (const auto hash = line.find('#'); hash != std::string::npos) line.erase(hash);
    std::istringstream ls(line);
    double v[5];
    int got = 0;
    std::string token;
    while (ls >> token) {
      if (got == 5)
        throw_invalid(where, fmt::format("line {}", number), line, "five numbers: value r g b a");
      char* end = nullptr;
      v[got] = std::strtod(token.c_str(), &end);
      if (end == token.c_str() || *end != '\0' || !std::isfinite(v[got]) || v[got] < 0 ||
          v[got] > 1)
        throw_invalid(where, fmt::format("line {} field {}", number, fields[got]), token,
                      "a number in [0, 1]");
      ++got;
    }
    if (got == 0) continue;
    if (got != 5)
      throw_invalid(where, fmt::format("line {}", number), line, "five numbers: value r g b a");
    if (!pts.empty() && !(v[0] > pts.back().value))
      throw_invalid(where, fmt::format("line {} field value", number), fmt::format("{}", v[0]),
                    fmt::format("greater than the previous value {}", pts.back().value));
    pts.push_back({v[0], v[1], v[2], v[3], v[4]});
  }
  if (pts.empty())
    throw_invalid(where, "transfer function", "no entries",
                  "at least one line \"value r g b a\" (numbers in [0, 1])");
  return pts;
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

}  // namespace masav::atom
