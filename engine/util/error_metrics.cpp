#include "engine/util/error_metrics.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "engine/core/error.h"

namespace masav {

ErrorStats compare(std::span<const double> got, std::span<const double> want, double rel_floor) {
  if (got.size() != want.size())
    throw Error("", "compare", fmt::format("{} values against {} reference values", got.size(),
                                           want.size()), "compare arrays of the same length");
  ErrorStats e;
  e.count = got.size();
  double diff2 = 0, ref2 = 0;
  for (size_t i = 0; i < got.size(); ++i) {
    if (!std::isfinite(got[i]) && std::isfinite(want[i])) {
      ++e.non_finite;
      continue;
    }
    const double d = std::abs(got[i] - want[i]);
    const double rel = d / std::max(std::abs(want[i]), rel_floor);
    e.max_abs = std::max(e.max_abs, d);
    if (rel > e.max_rel) e.max_rel = rel, e.worst = i;
    diff2 += d * d;
    ref2 += want[i] * want[i];
  }
  e.rel_l2 = std::sqrt(diff2) / std::max(std::sqrt(ref2), 1e-300);
  return e;
}

ErrorStats compare(std::span<const float> got, std::span<const double> want, double rel_floor) {
  std::vector<double> wide(got.begin(), got.end());
  return compare(std::span<const double>(wide), want, rel_floor);
}

std::string describe(const ErrorStats& e) {
  return fmt::format("rel L2 {:.3g}, max rel {:.3g} (at {}), max abs {:.3g}{}", e.rel_l2, e.max_rel,
                     e.worst, e.max_abs,
                     e.non_finite ? fmt::format(", {} non-finite", e.non_finite) : "");
}

std::vector<double> xyz_components(std::span<const Vec4d> v) {
  std::vector<double> out;
  out.reserve(3 * v.size());
  for (const auto& a : v) out.insert(out.end(), {a.x, a.y, a.z});
  return out;
}

double rms(std::span<const double> v) {
  double s = 0;
  for (double x : v) s += x * x;
  return std::sqrt(s / double(std::max<size_t>(1, v.size())));
}

}  // namespace masav
