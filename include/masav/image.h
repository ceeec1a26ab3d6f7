#pragma once
/// \file
/// Images the raymarch produces, and PNG output.
#include <cstdint>
#include <string>
#include <vector>

#include "engine/core/types.h"

namespace masav {

/// A rendered image: premultiplied RGBA in [0, 1], top row first.
struct Image {
  uint32_t width = 0;         ///< pixels per row
  uint32_t height = 0;        ///< rows
  std::vector<Vec4d> pixels;  ///< width * height values, row by row
};

/// Writes `image` composited over black as an 8-bit PNG, gamma-encoded as `masav volume`
/// writes it (to a temporary name, then renamed). Throws masav::Error naming the path when it
/// cannot be written.
void save_png(const std::string& path, const Image& image);

}  // namespace masav
