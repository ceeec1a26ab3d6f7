#pragma once
// Two-sample chi-square test of histograms (for statistical kernels such as the scattering
// table): are two sets of counts drawn from the same distribution? Bins empty in both are
// left out; with equal totals one degree of freedom is lost to the constraint.
#include <cstdint>
#include <span>

namespace masav {

struct ChiSquare {
  double statistic = 0;
  double dof = 0;
  double p_value = 1;  // probability of a statistic this large if both come from one distribution
};

ChiSquare chi_square_two_sample(std::span<const double> a, std::span<const double> b);
// Regularised upper incomplete gamma Q(s, x) = Gamma(s, x) / Gamma(s).
double gamma_q(double s, double x);

}  // namespace masav
