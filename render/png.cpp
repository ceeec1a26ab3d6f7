#include "render/png.h"

#include <fmt/format.h>
#include <stb_image.h>
#include <stb_image_write.h>

#include "engine/core/error.h"
#include "engine/util/json_writer.h"

namespace masav::render {

void write_png(const std::string& path, uint32_t width, uint32_t height,
               const std::vector<uint8_t>& rgba) {
  if (rgba.size() != size_t(width) * height * 4)
    throw Error("", "png",
                fmt::format("{} bytes for a {}x{} RGBA image", rgba.size(), width, height),
                "internal error");
  std::string encoded;
  const auto sink = [](void* ctx, void* data, int size) {
    static_cast<std::string*>(ctx)->append(static_cast<const char*>(data), size_t(size));
  };
  if (!stbi_write_png_to_func(sink, &encoded, int(width), int(height), 4, rgba.data(),
                              int(width) * 4))
    throw Error("", "png", fmt::format("encoding '{}' failed", path), "report this");
  write_file_atomic(path, encoded);
}

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
