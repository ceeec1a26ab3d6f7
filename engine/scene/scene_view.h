#pragma once
// What a scene hands the renderer: backend buffers and how to draw them, no graphics types.
// The renderer binds them directly when the compute backend is Vulkan on its own device, and
// copies them (only when their version changed) from CUDA or the CPU reference otherwise.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "engine/core/buffer.h"
#include "engine/core/types.h"

namespace masav::scene {

// Particles drawn as point sprites, coloured by a per-point scalar through the colour map.
struct PointLayer {
  const Buffer<Real4>* positions = nullptr;  // xyz; w holds a per-point value
  uint32_t count = 0;
  enum class ScalarFrom : uint8_t {
    buffer,      // `scalar`: u32, f32 or real per point, in the same order as `positions`
    position_w,  // positions[i].w
    position_z,  // height
    none,        // one colour (the colour map's middle)
    // `scalar` is a real4 buffer (e.g. velocities): the length of each element's xyz.
    vector_length,
  };
  ScalarFrom from = ScalarFrom::none;
  const BufferImpl* scalar = nullptr;
  float scalar_lo = 0, scalar_hi = 1;  // colour-map range
  // For the legend and the colour bar: "quantity (unit)", e.g. "speed (m/s)".
  std::string scalar_name;
  std::string scalar_key;  // the quantity alone, for exported arrays: "speed"
  // The legend, the colour bar and render.range_min/max show scalar * shown_per_unit (the
  // atom's light buffer holds the light at a reference power; the legend, at the current one).
  float shown_per_unit = 1;
  // Points whose position w is below this are drawn in grey whatever their scalar (the SPH
  // scene's obstacle particles, whose w is their inverse mass scale).
  std::optional<float> marker_below_w;
  uint64_t version = 0;  // changes when positions or scalars change
};

// What an image's colours stand for, for the colour bar: `colours` evenly spaced from `lo` to
// `hi` of the quantity named in `title` ("quantity (unit)").
struct ColourKey {
  std::string title;
  float lo = 0, hi = 1;
  std::vector<Vec4f> colours;
};

// An image computed on the backend (the raymarch; the particle demo's star field), drawn as a
// full-screen quad behind everything else: colour = gain * pixel^gamma (per channel).
struct ImageLayer {
  const BufferImpl* pixels = nullptr;
  uint32_t width = 0, height = 0;
  enum class Format : uint8_t {
    rgba8,    // u32 per pixel, r in the low byte
    rgba32f,  // four f32 (or real) per pixel
  };
  Format format = Format::rgba32f;
  float gain = 1.0f, gamma = 1.0f;
  bool mono = false;             // use the red channel for all three
  std::optional<ColourKey> key;  // none: the image's colours stand for no one quantity
  uint64_t version = 0;
};

struct Box {
  Vec3f lo{0, 0, 0}, hi{1, 1, 1};
};

struct SceneView {
  std::optional<PointLayer> points;
  std::optional<ImageLayer> background;
  Box box;
};

}  // namespace masav::scene
