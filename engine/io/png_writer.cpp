#include "engine/io/png_writer.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "engine/core/error.h"
#include "engine/util/json_writer.h"

#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STBI_WRITE_NO_STDIO
#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wunused-parameter"
#endif
#include <stb/stb_image_write.h>
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif

namespace masav {

void write_png(const std::string& path, uint32_t width, uint32_t height,
               const std::vector<uint8_t>& rgba) {
  if (width == 0 || height == 0 || rgba.size() != size_t(width) * height * 4)
    throw Error("", "png", fmt::format("{} bytes for a {}x{} RGBA image", rgba.size(), width, height),
                "internal error: report it");
  std::string out;
  auto sink = [](void* ctx, void* data, int size) {
    static_cast<std::string*>(ctx)->append(static_cast<const char*>(data), size_t(size));
  };
  if (!stbi_write_png_to_func(sink, &out, int(width), int(height), 4, rgba.data(), int(width * 4)))
    throw Error("", "png", fmt::format("encoding '{}' failed", path), "report it");
  write_file_atomic(path, out);
}

std::vector<uint8_t> to_rgba8(const std::vector<Vec4d>& image, Vec3f bg, bool gamma) {
  std::vector<uint8_t> out(image.size() * 4);
  auto enc = [gamma](double v) {
    v = std::clamp(v, 0.0, 1.0);
    if (gamma) v = std::pow(v, 1.0 / 2.2);
    return uint8_t(std::lround(v * 255.0));
  };
  for (size_t i = 0; i < image.size(); ++i) {
    const Vec4d& c = image[i];
    const double t = 1.0 - std::clamp(c.w, 0.0, 1.0);
    out[4 * i] = enc(c.x + t * bg.x);
    out[4 * i + 1] = enc(c.y + t * bg.y);
    out[4 * i + 2] = enc(c.z + t * bg.z);
    out[4 * i + 3] = 255;
  }
  return out;
}

}  // namespace masav
