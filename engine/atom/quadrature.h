#pragma once
// Gauss-Legendre quadrature on an interval (8 points: exact for polynomials of degree 15), used
// on the host to integrate |psi|^2 factors over the sampling tables' bins and in the tests.
#include <array>

namespace masav::atom {

template <class F>
double gauss_legendre8(F&& f, double a, double b) {
  static constexpr std::array<double, 4> x = {0.1834346424956498, 0.5255324099163290,
                                              0.7966664774136267, 0.9602898564975363};
  static constexpr std::array<double, 4> w = {0.3626837833783620, 0.3137066458778873,
                                              0.2223810344533745, 0.1012285362903763};
  const double c = 0.5 * (a + b), h = 0.5 * (b - a);
  double s = 0;
  for (int i = 0; i < 4; ++i) s += w[i] * (f(c - h * x[i]) + f(c + h * x[i]));
  return s * h;
}

// Composite 8-point rule over `pieces` equal sub-intervals.
template <class F>
double integrate(F&& f, double a, double b, int pieces) {
  double s = 0;
  for (int i = 0; i < pieces; ++i)
    s += gauss_legendre8(f, a + (b - a) * i / pieces, a + (b - a) * (i + 1) / pieces);
  return s;
}

}  // namespace masav::atom
