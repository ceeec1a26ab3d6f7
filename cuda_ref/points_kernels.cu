// drift_points: a thin wrapper around engine/kernels/drift.h in fp32.
#include "cuda_ref/cuda_launch.h"
#include "cuda_ref/points_launch.h"
#include "engine/kernels/drift.h"

namespace masav::cuda::launch {
namespace {

__global__ void drift_kernel(DriftArgs a, const float4* start, const float4* direction,
                             float4* positions) {
  const uint64_t i = (uint64_t(blockIdx.y) * gridDim.x + blockIdx.x) * blockDim.x + threadIdx.x;
  if (i >= a.n) return;
  const float4 u4 = start[i], w4 = direction[i];
  const float u[3] = {u4.x, u4.y, u4.z}, w[3] = {w4.x, w4.y, w4.z};
  const float speed_t = hd::mul_rn(a.speed, a.time_s);
  float p[3];
  float v2 = 0.0f;
  for (int k = 0; k < 3; ++k) {
    p[k] = hd::add_rn(a.lo[k], hd::mul_rn(a.extent[k], drift::axis_fraction(u[k], w[k], speed_t)));
    const float v = drift::axis_velocity(w[k], a.speed, a.extent[k]);
    v2 = hd::add_rn(v2, hd::mul_rn(v, v));
  }
  positions[i] = make_float4(p[0], p[1], p[2], __fsqrt_rn(v2));
}

}  // namespace

cudaError_t drift_points(cudaStream_t s, dim3 grid, DriftArgs a, const float4* start,
                         const float4* direction, float4* positions) {
  drift_kernel<<<grid, kBlock, 0, s>>>(a, start, direction, positions);
  return cudaGetLastError();
}

}  // namespace masav::cuda::launch
