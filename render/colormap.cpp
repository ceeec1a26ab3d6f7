#include "render/colormap.h"

#include <vector>

#include "engine/core/error.h"

namespace masav::render {
namespace {

Vec4f hex(uint32_t rgb) {
  return {float((rgb >> 16) & 255) / 255.0f, float((rgb >> 8) & 255) / 255.0f,
          float(rgb & 255) / 255.0f, 1.0f};
}

ColormapTable interpolate(const std::vector<Vec4f>& anchors) {
  ColormapTable t;
  const size_t segments = anchors.size() - 1;
  for (size_t i = 0; i < t.size(); ++i) {
    const float x = float(i) / float(t.size() - 1) * float(segments);
    const size_t k = std::min(size_t(x), segments - 1);
    const float f = x - float(k);
    const Vec4f& a = anchors[k];
    const Vec4f& b = anchors[k + 1];
    t[i] = {a.x + (b.x - a.x) * f, a.y + (b.y - a.y) * f, a.z + (b.z - a.z) * f, 1.0f};
  }
  return t;
}

}  // namespace

ColormapTable colormap_table(std::string_view name) {
  if (name == "viridis")
    return interpolate({hex(0x440154), hex(0x472D7B), hex(0x3B528B), hex(0x2C728E), hex(0x21918C),
                        hex(0x28AE80), hex(0x5EC962), hex(0xADDC30), hex(0xFDE725)});
  if (name == "inferno")
    return interpolate({hex(0x000004), hex(0x1F0C48), hex(0x550F6D), hex(0x88226A), hex(0xBA3655),
                        hex(0xE35933), hex(0xF98C0A), hex(0xF9C932), hex(0xFCFFA4)});
  if (name == "thesis") return interpolate({hex(0x0000FF), hex(0x00FF00), hex(0xFF0000)});
  if (name == "grey") return interpolate({hex(0x202020), hex(0xFFFFFF)});
  throw_invalid("render", "render.colormap", std::string(name),
                "one of viridis, inferno, thesis, grey");
}

}  // namespace masav::render
