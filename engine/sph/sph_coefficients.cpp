#include "engine/sph/sph_coefficients.h"

#include <cmath>
#include <numbers>

namespace masav {

sph::Coefficients<double> make_coefficients(const SphStepParams& p) {
  constexpr double pi = std::numbers::pi;
  const double h = p.h;
  sph::Coefficients<double> c{};
  c.h2 = h * h;
  c.inv_h = 1.0 / h;
  c.inv_h2 = 1.0 / (h * h);
  c.density = p.mass * 315.0 / (64.0 * pi * h * h * h);
  const bool thesis = p.model == SphPressureModel::thesis;
  c.pressure = thesis ? p.kp * p.mass * 45.0 / (pi * h * h * h) / 2.0
                      : p.gradient_correction * p.mass * 45.0 / (pi * h * h * h * h);
  c.viscosity = p.viscosity * p.mass * 45.0 / (pi * std::pow(h, 5));
  c.rest_density = p.rest_density;
  c.inv_rest_density = 1.0 / p.rest_density;
  const double cs = signal_speed(p);
  c.eos = thesis ? cs * cs : p.rest_density * p.sound_speed * p.sound_speed / 7.0;
  c.gravity[0] = p.gravity.x;
  c.gravity[1] = p.gravity.y;
  c.gravity[2] = p.gravity.z;
  c.lo[0] = p.box_min.x;
  c.lo[1] = p.box_min.y;
  c.lo[2] = p.box_min.z;
  c.hi[0] = p.box_max.x;
  c.hi[1] = p.box_max.y;
  c.hi[2] = p.box_max.z;
  c.walls = p.walls && !thesis ? 1u : 0u;
  c.wall_viscosity = p.viscosity * 7.5 / (h * h);
  c.wall_offset = p.wall_offset;
  c.model = thesis ? sph::kModelThesis : sph::kModelWcsph;
  c.clamp_negative_pressure = p.clamp_negative_pressure ? 1u : 0u;
  return c;
}

sph::Coefficients<float> to_float(const sph::Coefficients<double>& c) {
  sph::Coefficients<float> f{};
  f.h2 = float(c.h2);
  f.inv_h = float(c.inv_h);
  f.inv_h2 = float(c.inv_h2);
  f.density = float(c.density);
  f.pressure = float(c.pressure);
  f.viscosity = float(c.viscosity);
  f.rest_density = float(c.rest_density);
  f.inv_rest_density = float(c.inv_rest_density);
  f.eos = float(c.eos);
  for (int a = 0; a < 3; ++a) {
    f.gravity[a] = float(c.gravity[a]);
    f.lo[a] = float(c.lo[a]);
    f.hi[a] = float(c.hi[a]);
  }
  f.walls = c.walls;
  f.wall_viscosity = float(c.wall_viscosity);
  f.wall_offset = float(c.wall_offset);
  f.model = c.model;
  f.clamp_negative_pressure = c.clamp_negative_pressure;
  return f;
}

double signal_speed(const SphStepParams& p) {
  if (p.model == SphPressureModel::thesis)
    return std::sqrt(3.0 / 14.0 * p.kp * p.rest_density * p.h);
  return p.sound_speed;
}

double tait_pressure(double rho, const SphStepParams& p) {
  const double b = p.rest_density * p.sound_speed * p.sound_speed / 7.0;
  const double pr = b * (std::pow(rho / p.rest_density, 7.0) - 1.0);
  return p.clamp_negative_pressure && pr < 0 ? 0.0 : pr;
}

double tait_internal_energy(double rho, const SphStepParams& p) {
  // e(rho) = B [ rho^6 / (6 rho0^7) + 1/rho ] - B [ 1/(6 rho0) + 1/rho0 ]: d e / d rho = p / rho^2.
  const double b = p.rest_density * p.sound_speed * p.sound_speed / 7.0;
  if (p.clamp_negative_pressure && rho < p.rest_density) return 0.0;
  const double r0 = p.rest_density;
  return b * (std::pow(rho / r0, 6.0) / (6.0 * r0) + 1.0 / rho) - b * (7.0 / (6.0 * r0));
}

}  // namespace masav
