#pragma once
// PNG files through stb (libstb): frames written to a temporary name and renamed, so an
// interrupted run never leaves a truncated image; reading is for tests and image checks.
#include <cstdint>
#include <string>
#include <vector>

#include "engine/io/png_writer.h"

namespace masav::render {

struct Rgba8Image {
  uint32_t width = 0, height = 0;
  std::vector<uint8_t> pixels;  // RGBA rows, top first
};

// Written by the engine's one PNG writer (to a temporary name, renamed).
using masav::write_png;
Rgba8Image read_png(const std::string& path);

}  // namespace masav::render
