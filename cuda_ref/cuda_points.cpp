// drift_points on CUDA, host side: checks, then the launch in points_kernels.cu.
#include "cuda_ref/cuda_backend.h"
#include "cuda_ref/cuda_check.h"
#include "cuda_ref/points_launch.h"

namespace masav::cuda {

void CudaBackend::do_drift_points(const DriftParams& p, uint64_t, const Buffer<float>& start,
                               const Buffer<float>& direction, Buffer<Real4>& positions) {
  const launch::DriftArgs a{{p.box_lo.x, p.box_lo.y, p.box_lo.z},
                            {p.box_extent.x, p.box_extent.y, p.box_extent.z},
                            p.speed,
                            p.time_s,
                            p.n};
  check(launch::drift_points(stream_, grid_for_items(p.n, "drift_points"), a,
                             static_cast<const float4*>(ptr(start.impl(), "drift_points")),
                             static_cast<const float4*>(ptr(direction.impl(), "drift_points")),
                             static_cast<float4*>(ptr(positions.impl(), "drift_points"))),
        "drift_points", "launch");
}

}  // namespace masav::cuda
