#pragma once
// PNG files through stb (libstb): frames written to a temporary name and renamed, so an
// interrupted run never leaves a truncated image; reading is for tests and image checks.
#include <cstdint>
#include <string>
#include <vector>

namespace masav::render {

struct Rgba8Image {
  uint32_t width = 0, height = 0;
  std::vector<uint8_t> pixels;  // RGBA rows, top first
};

void write_png(const std::string& path, uint32_t width, uint32_t height,
               const std::vector<uint8_t>& rgba);
Rgba8Image read_png(const std::string& path);

}  // namespace masav::render
