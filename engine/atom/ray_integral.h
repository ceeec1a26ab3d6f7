#pragma once
// The exact integral of a linear ramp along a ray: the analytic reference that the raymarch's
// quadrature error is measured against (bench raymarch's step sweep, the raymarch tests).
#include <algorithm>
#include <utility>

namespace masav::atom {

// int_{t0}^{t1} clamp(o + t d, lo, hi) dt, exactly.
inline double clamped_linear_integral(double o, double d, double lo, double hi, double t0,
                                      double t1) {
  if (d == 0) return std::clamp(o, lo, hi) * (t1 - t0);
  double ta = (lo - o) / d, tb = (hi - o) / d;
  if (ta > tb) std::swap(ta, tb);
  const double a = std::clamp(ta, t0, t1), b = std::clamp(tb, t0, t1);
  const double below = d > 0 ? lo : hi, above = d > 0 ? hi : lo;
  return below * (a - t0) + (o * (b - a) + 0.5 * d * (b * b - a * a)) + above * (t1 - b);
}

}  // namespace masav::atom
