#include "engine/sph/sph_coefficients.h"

#include <cmath>

namespace masav {

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
