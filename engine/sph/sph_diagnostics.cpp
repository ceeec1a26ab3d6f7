#include "engine/sph/sph_diagnostics.h"

#include <algorithm>
#include <cmath>

#include "engine/sph/sph_coefficients.h"

namespace masav {

SphDiagnostics compute_diagnostics(const SphState& s, const SphSimulation& sim) {
  const SphScene& sc = sim.scene();
  const SphParticles& lay = sim.layout();
  const SphStepParams sp = sim.step_params();
  const double m = lay.mass;
  const double thesis_c2 = signal_speed(sp) * signal_speed(sp);
  SphDiagnostics d;
  double fluid_mass = 0;
  std::vector<double> compressions;
  compressions.reserve(lay.fluid);
  d.surge_front = -1e300;
  // fp32 backends clamp to the box as rounded to float: a particle resting on a wall may sit half
  // an ulp of the coordinate outside the double box (float(0.73) > 0.73), which is not a leak.
  auto ulp_tol = [](double v) { return 1e-6 * std::max(1.0, std::abs(v)); };
  const Vec3d lo{sc.box_min.x - ulp_tol(sc.box_min.x), sc.box_min.y - ulp_tol(sc.box_min.y),
                 sc.box_min.z - ulp_tol(sc.box_min.z)};
  const Vec3d hi{sc.box_max.x + ulp_tol(sc.box_max.x), sc.box_max.y + ulp_tol(sc.box_max.y),
                 sc.box_max.z + ulp_tol(sc.box_max.z)};
  for (size_t i = 0; i < s.positions.size(); ++i) {
    const Vec4d& x = s.positions[i];
    const Vec4d& v = s.velocities[i];
    if (!std::isfinite(x.x) || !std::isfinite(x.y) || !std::isfinite(x.z) || !std::isfinite(v.x) ||
        !std::isfinite(v.y) || !std::isfinite(v.z))
      d.finite = false;
    if (x.x < lo.x || x.y < lo.y || x.z < lo.z || x.x > hi.x || x.y > hi.y || x.z > hi.z)
      ++d.outside;
    if (sc.model == SphPressureModel::wcsph) {
      // The force scales every pressure by the lattice's gradient correction (the wcsph
      // c.pressure), so the energy it stores is that much larger too.
      d.internal += m * sp.gradient_correction * tait_internal_energy(s.density[i], sp);
    } else if (sc.model == SphPressureModel::thesis && s.density[i] > 0) {
      // The thesis force is an isothermal gas's (signal_speed): e = c^2 ln(rho / rho0).
      d.internal += m * thesis_c2 * std::log(s.density[i] / sc.rest_density);
    }
    if (x.w > 0) {
      const double big_m = m / x.w;
      const double v2 = v.x * v.x + v.y * v.y + v.z * v.z;
      d.kinetic += 0.5 * big_m * v2;
      d.potential -= big_m * (sc.gravity.x * x.x + sc.gravity.y * x.y + sc.gravity.z * x.z);
      d.momentum.x += big_m * v.x;
      d.momentum.y += big_m * v.y;
      d.momentum.z += big_m * v.z;
      d.momentum_scale += big_m * std::sqrt(v2);
      d.max_speed = std::max(d.max_speed, std::sqrt(v2));
    }
    if (i < lay.fluid) {
      fluid_mass += m;
      d.center_of_mass.x += m * x.x;
      d.center_of_mass.y += m * x.y;
      d.center_of_mass.z += m * x.z;
      d.mean_density += s.density[i];
      d.max_density = std::max(d.max_density, s.density[i]);
      const double compression = std::max(s.density[i] / sc.rest_density - 1.0, 0.0);
      d.mean_compression += compression;
      d.max_compression = std::max(d.max_compression, compression);
      compressions.push_back(compression);
      d.surge_front = std::max(d.surge_front, x.x);
    }
  }
  if (lay.fluid) {
    d.center_of_mass.x /= fluid_mass;
    d.center_of_mass.y /= fluid_mass;
    d.center_of_mass.z /= fluid_mass;
    d.mean_density /= double(lay.fluid);
    d.mean_compression /= double(lay.fluid);
    d.surge_front += 0.5 * lay.placed_dx;
  }
  if (!compressions.empty()) {
    // The smallest value that at least 99.9% of the particles do not exceed.
    const size_t k = size_t(std::ceil(0.999 * double(compressions.size()))) - 1;
    std::nth_element(compressions.begin(), compressions.begin() + std::ptrdiff_t(k),
                     compressions.end());
    d.p999_compression = compressions[k];
  }
  return d;
}

std::vector<std::string> diagnostics_columns() {
  return {"step",           "time_s",        "dt_s",
          "kinetic_J",      "potential_J",   "internal_J",
          "total_J",        "momentum_x",    "momentum_y",
          "momentum_z",     "max_speed",     "mean_density",
          "max_density",    "com_x",         "com_y",
          "com_z",          "surge_front_m", "max_neighbors",
          "retries",        "outside",       "mean_compression",
          "max_compression", "p999_compression"};
}

std::vector<double> diagnostics_row(const SphSimulation& sim, const SphDiagnostics& d) {
  return {double(sim.steps()),
          sim.time(),
          sim.last_dt(),
          d.kinetic,
          d.potential,
          d.internal,
          d.total(),
          d.momentum.x,
          d.momentum.y,
          d.momentum.z,
          d.max_speed,
          d.mean_density,
          d.max_density,
          d.center_of_mass.x,
          d.center_of_mass.y,
          d.center_of_mass.z,
          d.surge_front,
          double(sim.last_stats().max_neighbors),
          double(sim.retries()),
          double(d.outside),
          d.mean_compression,
          d.max_compression,
          d.p999_compression};
}

}  // namespace masav
