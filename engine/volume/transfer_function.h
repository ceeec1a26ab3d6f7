#pragma once
// 1-D transfer functions for raymarch: RGBA over the normalised scalar [0, 1], as `size`
// entries that the kernels interpolate linearly. The default runs blue -> green -> red (thesis
// §3.4: low to high radiance) with opacity rising with the value; a text file of control
// points can replace it.
#include <cstdint>
#include <string>
#include <vector>

#include "engine/core/types.h"

namespace masav::volume {

struct TransferPoint {
  double value;  // in [0, 1], ascending
  double r, g, b, a;
};

std::vector<TransferPoint> default_transfer_points();
// Lines "value r g b a" (all in [0, 1], values ascending); '#' starts a comment. Errors name
// the file, the line and the field; a file with no entries is an error.
std::vector<TransferPoint> load_transfer_points(const std::string& path);
std::vector<TransferPoint> parse_transfer_points(const std::string& text, const std::string& where);
// The same points inline, as the scene key `key` holds them: "value r g b a; value r g b a;
// ...". The same checks; errors name the key, the point (1-based) and the field.
std::vector<TransferPoint> parse_inline_transfer(const std::string& text, const std::string& key);
std::string format_inline_transfer(const std::vector<TransferPoint>& points);
// The text of a transfer function file (a comment line, then "value r g b a" per line) that
// load_transfer_points reads back as the same points.
std::string format_transfer_file(const std::vector<TransferPoint>& points);
// Piecewise-linear resampling to `size` entries (constant beyond the first and last points).
std::vector<Vec4d> resample_transfer(const std::vector<TransferPoint>& points, uint32_t size = 256);

}  // namespace masav::volume
