#include "render/png.h"

#include <fmt/format.h>
#include <stb_image.h>

#include "engine/core/error.h"

namespace masav::render {

Rgba8Image read_png(const std::string& path) {
  int w = 0, h = 0, channels = 0;
  unsigned char* data = stbi_load(path.c_str(), &w, &h, &channels, 4);
  if (!data)
    throw Error("", "png", fmt::format("cannot read '{}': {}", path, stbi_failure_reason()),
                "give the path of a PNG image");
  Rgba8Image img{uint32_t(w), uint32_t(h),
                 std::vector<uint8_t>(data, data + size_t(w) * size_t(h) * 4)};
  stbi_image_free(data);
  return img;
}

}  // namespace masav::render
