#include "engine/points/drift_compare.h"

#include <algorithm>
#include <cmath>

#include "engine/core/error.h"

namespace masav {

DriftError compare_drift(const DriftParams& p, std::span<const Vec4d> got,
                         std::span<const Vec4d> want) {
  if (got.size() != want.size())
    throw Error("", "compare_drift", "outputs of different lengths", "compare equal runs");
  const double ext[3] = {p.box_extent.x, p.box_extent.y, p.box_extent.z};
  DriftError e;
  for (size_t i = 0; i < got.size(); ++i) {
    const double g[4] = {got[i].x, got[i].y, got[i].z, got[i].w};
    const double w[4] = {want[i].x, want[i].y, want[i].z, want[i].w};
    bool finite = true;
    for (double v : g) finite = finite && std::isfinite(v);
    if (!finite) {
      ++e.non_finite;
      continue;
    }
    for (int a = 0; a < 3; ++a) {
      double d = std::abs(g[a] - w[a]);
      d = std::min(d, std::abs(ext[a] - d));  // across the periodic boundary
      if (d > e.max_position_abs) e.max_position_abs = d, e.worst = i;
    }
    const double rel = std::abs(g[3] - w[3]) / std::max(std::abs(w[3]), 1e-30);
    e.max_speed_rel = std::max(e.max_speed_rel, rel);
  }
  return e;
}

DriftTolerance drift_tolerance(const DriftParams& p) {
  constexpr double ulp = 0x1p-24;
  const double st = std::abs(double(p.speed) * p.time_s);
  double tol = 0;
  const double lo[3] = {p.box_lo.x, p.box_lo.y, p.box_lo.z};
  const double ext[3] = {p.box_extent.x, p.box_extent.y, p.box_extent.z};
  for (int a = 0; a < 3; ++a)
    tol = std::max(tol, ext[a] * (3 * st + 2) * ulp + (std::abs(lo[a]) + ext[a]) * ulp);
  return DriftTolerance{4 * tol, 1e-5};
}

}  // namespace masav
