#include "engine/volume/value_histogram.h"

#include <algorithm>
#include <cmath>

#include "engine/core/error.h"

namespace masav::volume {

std::vector<uint32_t> value_histogram(std::span<const double> values, double lo, double hi,
                                      uint32_t bins) {
  if (bins < 1) throw_invalid("value histogram", "bins", "0", "at least 1");
  std::vector<uint32_t> counts(bins, 0);
  const double width = hi - lo;
  for (const double v : values) {
    if (!std::isfinite(v)) continue;
    const double t = width > 0 ? std::clamp((v - lo) / width, 0.0, 1.0) : 0.0;
    ++counts[std::min<size_t>(size_t(t * bins), bins - 1)];
  }
  return counts;
}

std::vector<float> log_heights(const std::vector<uint32_t>& counts) {
  uint32_t top = 0;
  for (const uint32_t c : counts) top = std::max(top, c);
  std::vector<float> h(counts.size(), 0.0f);
  if (top == 0) return h;
  const double scale = 1.0 / std::log1p(double(top));
  for (size_t i = 0; i < counts.size(); ++i) h[i] = float(std::log1p(double(counts[i])) * scale);
  return h;
}

}  // namespace masav::volume
