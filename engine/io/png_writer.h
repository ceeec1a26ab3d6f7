#pragma once
// PNG images (stb_image_write), written to a temporary name and renamed.
#include <cstdint>
#include <string>
#include <vector>

#include "engine/core/types.h"

namespace masav {

// 8-bit RGBA rows, top row first.
void write_png(const std::string& path, uint32_t width, uint32_t height,
               const std::vector<uint8_t>& rgba);
// Premultiplied float RGBA (as raymarch writes it) composited over `background`, clamped to
// [0, 1], optionally gamma-encoded (sRGB-like 1/2.2).
std::vector<uint8_t> to_rgba8(const std::vector<Vec4d>& image, Vec3f background = {0, 0, 0},
                              bool gamma = true);

}  // namespace masav
