#include "engine/sph/sph_watchdog.h"

#include <algorithm>
#include <cmath>

#include "engine/sph/sph_coefficients.h"
#include "engine/sph/sph_diagnostics.h"
#include "engine/sph/sph_simulation.h"

namespace masav {

double available_energy(const SphState& s, const SphSimulation& sim) {
  const SphScene& sc = sim.scene();
  // The box corner where -g . x is lowest.
  const Vec3d g = sc.gravity;
  const double floor_x = g.x > 0 ? sc.box_max.x : sc.box_min.x;
  const double floor_y = g.y > 0 ? sc.box_max.y : sc.box_min.y;
  const double floor_z = g.z > 0 ? sc.box_max.z : sc.box_min.z;
  const double per_kg = -(g.x * floor_x + g.y * floor_y + g.z * floor_z);
  double moving_mass = 0;
  for (const Vec4d& x : s.positions)
    if (x.w > 0) moving_mass += sim.layout().mass / x.w;
  return compute_diagnostics(s, sim).total() - per_kg * moving_mass;
}

SphWatchdog make_watchdog(const SphState& s, const SphSimulation& sim, double max_density) {
  const SphScene& sc = sim.scene();
  // The scene's speed of sound c0 (the wcsph signal speed; the thesis model's kp-derived one can
  // be arbitrarily large, and a gas flung at it, e.g. kp = 1e9, is the blow-up to catch).
  const double c = sc.sound_speed;
  const double g = std::hypot(sc.gravity.x, sc.gravity.y, sc.gravity.z);
  const double diag = std::hypot(sc.box_max.x - sc.box_min.x, sc.box_max.y - sc.box_min.y,
                                 sc.box_max.z - sc.box_min.z);
  double v0 = 0;
  for (const Vec4d& v : s.velocities) v0 = std::max(v0, std::hypot(v.x, v.y, v.z));
  SphWatchdog w;
  w.max_speed = std::max({2 * c, 2 * std::sqrt(2 * g * diag), 2 * v0});
  // Tait's gamma = 7 makes 2 rho0 127 times its pressure scale (an inviscid water drop's impact
  // legally spikes to 1.5 rho0); the thesis force is an isothermal gas's, which legitimately
  // compresses further (stress suite: up to 1.6 rho0).
  const double factor = sc.model == SphPressureModel::thesis ? 3.0 : 2.0;
  w.max_density = factor * std::max(sc.rest_density, max_density);
  w.energy0 = available_energy(s, sim);
  return w;
}

std::string watchdog_remedy() {
  // Whether that state is also written is the caller's to say (masav sph: with --out-dir).
  return "the fluid blew up; the simulation stays at its last good step: use a smaller "
         "dt or the adaptive dt, turn the CFL guard on (--cfl-guard reduce), lower kp or raise "
         "sound_speed, raise viscosity";
}

}  // namespace masav
