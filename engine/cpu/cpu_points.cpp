// drift_points on the CPU reference, in double precision (engine/kernels/drift.h).
#include <cmath>

#include "engine/cpu/cpu_backend.h"
#include "engine/kernels/drift.h"

namespace masav::cpu {

void CpuBackend::do_drift_points(const DriftParams& p, uint64_t, const Buffer<float>& start,
                              const Buffer<float>& direction, Buffer<Real4>& positions) {
  const float* u = own(start.impl(), "drift_points").as<float>();
  const float* w = own(direction.impl(), "drift_points").as<float>();
  double* out = own(positions.impl(), "drift_points").as<double>();
  const double lo[3] = {p.box_lo.x, p.box_lo.y, p.box_lo.z};
  const double ext[3] = {p.box_extent.x, p.box_extent.y, p.box_extent.z};
  const double speed = p.speed, speed_t = double(p.speed) * double(p.time_s);
  pool_.parallel_for(p.n, 8192, [&](size_t b, size_t e) {
    for (size_t i = b; i < e; ++i) {
      double v2 = 0;
      for (int a = 0; a < 3; ++a) {
        const double ua = u[4 * i + a], wa = w[4 * i + a];
        out[4 * i + a] = lo[a] + ext[a] * drift::axis_fraction(ua, wa, speed_t);
        const double v = drift::axis_velocity(wa, speed, ext[a]);
        v2 += v * v;
      }
      out[4 * i + 3] = std::sqrt(v2);
    }
  });
}

}  // namespace masav::cpu
