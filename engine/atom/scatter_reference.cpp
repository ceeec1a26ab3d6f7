#include "engine/atom/scatter_reference.h"

#include <algorithm>
#include <cmath>

#include "engine/atom/quadrature.h"

namespace masav::atom {

double henyey_greenstein_pdf(double g, double mu) {
  return 0.5 * (1 - g * g) / std::pow(1 + g * g - 2 * g * mu, 1.5);
}

std::vector<double> single_scattering(double tau, double g, uint32_t bins) {
  std::vector<double> out(bins);
  for (uint32_t j = 0; j < bins; ++j) {
    const double lo = -1 + 2.0 * j / bins, hi = -1 + 2.0 * (j + 1) / bins;
    out[j] = integrate([&](double s) {
      const double z = s - 1;
      return tau * std::exp(-tau * s) * integrate([&](double mu) {
        const double L = -z * mu + std::sqrt(std::max(0.0, 1 - z * z * (1 - mu * mu)));
        return henyey_greenstein_pdf(g, mu) * std::exp(-tau * L);
      }, lo, hi, 2);
    }, 0, 2, 48);
  }
  return out;
}

}  // namespace masav::atom
