#include "engine/atom/scatter_threshold.h"

#include <cmath>

namespace masav::atom {

float separated_weight_threshold(float albedo, float threshold, uint32_t max_scatterings) {
  if (!(albedo > 0 && albedo < 1) || !(threshold > 0)) return threshold;
  const double a = albedo, t = threshold;
  double above = 1.0;  // albedo^(k-1) >= t, in double
  float wf = 1.0f;     // the same power as fp32 multiplies it
  for (uint32_t k = 1; k <= max_scatterings + 1; ++k) {
    const double below = above * a;
    wf *= albedo;
    if (below < t) {
      // fp32 rounds once per scattering: a margin of a few ulps per step separates them.
      const double margin = 4e-7 * k;
      // A power equal to the threshold up to rounding is kept (it is not below it): the
      // threshold moves under it, to the middle of it and the next power.
      if (below > t * (1 - margin)) return float(below * std::sqrt(a));
      if (above < t * (1 + margin) || (wf < threshold) != (below < t))
        return float(std::sqrt(above * below));
      return threshold;
    }
    above = below;
  }
  return threshold;  // never reached within max_scatterings: the threshold plays no part
}

}  // namespace masav::atom
