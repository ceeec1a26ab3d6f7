#include "engine/sph/sph_scene_options.h"

#include <fmt/format.h>

#include "engine/core/error.h"
#include "engine/sph/sph_presets.h"

namespace masav {

SphScene make_sph_scene(const SphSceneOptions& o, std::string_view where_view) {
  const std::string where(where_view);
  const std::string preset = o.preset == "dambreak" ? "dam-break" : o.preset;
  if (o.particles == 0) throw_invalid(where, "particles", "0", "at least 1");
  SphScene s = make_preset(preset, o.particles);
  if (o.integrator) s.integrator = parse_integrator(*o.integrator, "integrator");
  if (o.pressure) s.model = parse_pressure_model(*o.pressure, "pressure");
  if (s.model == SphPressureModel::dfsph && !o.integrator)
    s.integrator = SphIntegrator::symplectic_euler;
  const bool dfsph = s.model == SphPressureModel::dfsph;
  const bool wcsph = s.model == SphPressureModel::wcsph;
  const bool c0 = o.sound_speed || o.max_compression;
  const char* c0_name = o.sound_speed ? "sound_speed" : "max_compression";
  if (dfsph && (o.kp || c0))
    throw Error("", where,
                fmt::format("{} conflicts with the dfsph pressure model, which solves for its "
                            "pressure instead",
                            o.kp ? "kp" : c0_name),
                "drop it, or use pressure wcsph (sound_speed, max_compression) or thesis (kp)");
  if (wcsph ? bool(o.kp) : c0)
    throw Error("", where,
                fmt::format("{} conflicts with the {} pressure model, which does not read it",
                            wcsph ? "kp" : c0_name, to_string(s.model)),
                wcsph ? "drop kp, or use pressure thesis"
                      : fmt::format("drop {}, or use pressure wcsph", c0_name));
  if (o.cfl_guard) s.cfl_guard = parse_cfl_guard(*o.cfl_guard, "cfl_guard");
  if (o.dt) s.dt = *o.dt;
  if (o.viscosity) s.viscosity = *o.viscosity;
  if (o.sound_speed) s.sound_speed = *o.sound_speed;
  if (o.max_compression) set_max_compression(s, *o.max_compression, "max_compression");
  if (o.kp) s.kp = *o.kp;
  if (o.smoothing_radius) s.smoothing_radius = *o.smoothing_radius;
  if (o.restitution) s.restitution = *o.restitution;
  if (o.seed) {
    if (s.jitter == 0)
      throw Error("", where,
                  fmt::format("seed changes nothing: the preset {} places its particles on a "
                              "lattice without jitter",
                              o.preset),
                  "drop seed");
    s.seed = *o.seed;
  }
  validate(s);
  return s;
}

}  // namespace masav
