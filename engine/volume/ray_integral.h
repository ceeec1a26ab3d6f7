#pragma once
// The exact integral of a linear ramp along a ray: the analytic reference that the raymarch's
// quadrature error is measured against (bench raymarch's step sweep, the raymarch tests).
#include <algorithm>
#include <cmath>
#include <utility>

namespace masav::volume {

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

// int_{t0}^{t1} kappa(v(t)) dt, exactly, for v(t) = scale * sum_a clamp(o_a + d_a t, lo, hi) (a
// linear volume seen along a ray, in voxel coordinates): v is linear between the (at most six) t
// where an axis reaches lo or hi, and over each such piece the integral is
// (K(v_b) - K(v_a)) / (dv/dt), with K the antiderivative of kappa.
template <class Extinction>
double clamped_ramp_depth(const double o[3], const double d[3], double lo, double hi, double scale,
                          double t0, double t1, const Extinction& e) {
  double cuts[8];
  int n = 0;
  cuts[n++] = t0;
  for (int a = 0; a < 3; ++a)
    if (d[a] != 0)
      for (double bound : {lo, hi}) {
        const double t = (bound - o[a]) / d[a];
        if (t > t0 && t < t1) cuts[n++] = t;
      }
  cuts[n++] = t1;
  // At most 8 cuts: insertion sort (std::sort's unrolled insertion trips GCC 12's array-bounds
  // warning on so short an array).
  for (int i = 1; i < n; ++i)
    for (int j = i; j > 0 && cuts[j] < cuts[j - 1]; --j) std::swap(cuts[j], cuts[j - 1]);
  auto v_at = [&](double t) {
    double v = 0;
    for (int a = 0; a < 3; ++a) v += std::clamp(o[a] + d[a] * t, lo, hi);
    return v * scale;
  };
  double depth = 0;
  for (int i = 0; i + 1 < n; ++i) {
    const double ta = cuts[i], tb = cuts[i + 1];
    if (tb <= ta) continue;
    const double va = v_at(ta), vb = v_at(tb);
    depth += std::abs(vb - va) < 1e-12
                 ? e(0.5 * (va + vb)) * (tb - ta)
                 : (e.antiderivative(vb) - e.antiderivative(va)) / (vb - va) * (tb - ta);
  }
  return depth;
}

// An extinction with a narrow peak: kappa(v) = c (v + height exp(-((v - at) / width)^2)) per
// unit length; a transfer function of such features is what pre-integration is for.
struct PeakedExtinction {
  double c = 1.5, at = 0.55, width = 0.01, height = 10;
  double operator()(double v) const {
    const double x = (v - at) / width;
    return c * (v + height * std::exp(-x * x));
  }
  double antiderivative(double v) const {
    return c * (0.5 * v * v + height * width * 0.886226925452758 * std::erf((v - at) / width));
  }
};

}  // namespace masav::volume
