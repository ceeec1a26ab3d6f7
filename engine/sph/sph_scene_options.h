#pragma once
// An SPH scene from `masav sph`'s options: a preset at a particle count, then each option given
// over it, with the command line's refusals of a constant the pressure model does not read and
// of a seed for a preset without jitter. The Python module and the public C++ API build their
// scenes with it, so every caller gets the same scene and the same messages.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "engine/sph/sph_params.h"

namespace masav {

struct SphSceneOptions {
  std::string preset = "water";  // a preset of sph_presets() ("dambreak" is "dam-break")
  uint32_t particles = 32768;
  std::optional<std::string> integrator, pressure, cfl_guard;  // as --integrator etc. name them
  std::optional<double> dt, viscosity, sound_speed, max_compression, kp, smoothing_radius,
      restitution;
  std::optional<uint64_t> seed;  // jittered presets only
};

// Throws masav::Error naming `where` and the option on a value out of range or a conflict.
SphScene make_sph_scene(const SphSceneOptions& o, std::string_view where);

}  // namespace masav
