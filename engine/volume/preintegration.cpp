// Depth and emission at each entry, and their integrals by the trapezoid rule (exact for the
// linear pieces the raymarch assumes), summed in double.
#include "engine/volume/preintegration.h"

#include <algorithm>
#include <cmath>

#include "engine/core/error.h"
#include "engine/kernels/atom_params.h"

namespace masav::volume {

std::vector<Vec4d> preintegrate_transfer(const std::vector<Vec4d>& tf) {
  if (tf.size() < 2)
    throw_invalid("transfer function", "size", std::to_string(tf.size()), "at least 2 entries");
  const size_t n = tf.size();
  std::vector<Vec4d> out(kPreintegratedPerEntry * n, Vec4d{0, 0, 0, 0});
  auto point = [&](size_t k) {
    const double alpha = std::clamp(tf[k].w, 0.0, 1.0);
    const double depth = -std::log(std::max(1.0 - alpha, kMinTransmittance));
    return Vec4d{tf[k].x * depth, tf[k].y * depth, tf[k].z * depth, depth};
  };
  double sum[4] = {0, 0, 0, 0};
  for (size_t k = 0; k < n; ++k) {
    const Vec4d p = point(k);
    out[kPreintegratedPerEntry * k] = p;
    if (k > 0) {
      const Vec4d q = point(k - 1);
      sum[0] += 0.5 * (q.x + p.x);
      sum[1] += 0.5 * (q.y + p.y);
      sum[2] += 0.5 * (q.z + p.z);
      sum[3] += 0.5 * (q.w + p.w);
    }
    double hi[4];
    for (int c = 0; c < 4; ++c) {
      // Through a volatile: GCC 12's SLP vectorizer at -O2 drops the rounding of the four
      // double(float(x)) together, which left every remainder 0.
      volatile float rounded = float(sum[c]);
      hi[c] = rounded;
    }
    out[kPreintegratedPerEntry * k + 1] = {hi[0], hi[1], hi[2], hi[3]};
    out[kPreintegratedPerEntry * k + 2] = {sum[0] - hi[0], sum[1] - hi[1], sum[2] - hi[2],
                                           sum[3] - hi[3]};
  }
  return out;
}

Buffer<Real4> upload_preintegrated(Backend& b, const std::vector<Vec4d>& tf) {
  const std::vector<Vec4d> table = preintegrate_transfer(tf);
  auto out = b.create<Real4>(table.size(), "pre-integrated transfer function");
  b.upload(out, table);
  return out;
}

}  // namespace masav::volume
