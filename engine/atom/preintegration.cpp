// Pieces integrated by the midpoint rule on 64 sub-intervals: the colour and alpha are linear in
// a piece but the depth -ln(1 - alpha) is not, and is singular where alpha reaches 1.
#include "engine/atom/preintegration.h"

#include <algorithm>
#include <cmath>

#include "engine/core/error.h"
#include "engine/kernels/atom_params.h"

namespace masav::atom {

std::vector<Vec4d> preintegrate_transfer(const std::vector<Vec4d>& tf) {
  if (tf.size() < 2)
    throw_invalid("transfer function", "size", std::to_string(tf.size()), "at least 2 entries");
  const size_t n = tf.size();
  std::vector<Vec4d> out(kPreintegratedPerEntry * n, Vec4d{0, 0, 0, 0});
  const int sub = 64;
  double sum[4] = {0, 0, 0, 0};
  for (size_t k = 0; k < n; ++k) {
    // The sums over pieces 0 .. k-1, split into a float and what the float left.
    Vec4d& hi = out[kPreintegratedPerEntry * k + 1];
    Vec4d& lo = out[kPreintegratedPerEntry * k + 2];
    double h[4];
    for (int c = 0; c < 4; ++c) {
      // Through a volatile: GCC 12's SLP vectorizer at -O2 drops the rounding of the four
      // double(float(x)) together, which left every remainder 0.
      volatile float rounded = float(sum[c]);
      h[c] = rounded;
    }
    hi = {h[0], h[1], h[2], h[3]};
    lo = {sum[0] - h[0], sum[1] - h[1], sum[2] - h[2], sum[3] - h[3]};
    if (k + 1 == n) break;
    const Vec4d& a = tf[k];
    const Vec4d& b = tf[k + 1];
    double mean[4] = {0, 0, 0, 0};
    for (int s = 0; s < sub; ++s) {
      const double w = (s + 0.5) / sub;
      const double alpha = std::clamp(a.w + (b.w - a.w) * w, 0.0, 1.0);
      const double depth = -std::log(std::max(1.0 - alpha, kMinTransmittance));
      mean[0] += (a.x + (b.x - a.x) * w) * depth;
      mean[1] += (a.y + (b.y - a.y) * w) * depth;
      mean[2] += (a.z + (b.z - a.z) * w) * depth;
      mean[3] += depth;
    }
    for (double& m : mean) m /= sub;
    out[kPreintegratedPerEntry * k] = {mean[0], mean[1], mean[2], mean[3]};
    for (int c = 0; c < 4; ++c) sum[c] += mean[c];
  }
  return out;
}

Buffer<Real4> upload_preintegrated(Backend& b, const std::vector<Vec4d>& tf) {
  const std::vector<Vec4d> table = preintegrate_transfer(tf);
  auto out = b.create<Real4>(table.size(), "pre-integrated transfer function");
  b.upload(out, table);
  return out;
}

}  // namespace masav::atom
