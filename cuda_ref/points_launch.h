#pragma once
// Launchers of the demo point-cloud kernels (points_kernels.cu).
#include <cuda_runtime_api.h>

#include <cstdint>

namespace masav::cuda::launch {

struct DriftArgs {
  float lo[3];
  float extent[3];
  float speed;
  float time_s;
  uint32_t n;
};

cudaError_t drift_points(cudaStream_t s, dim3 grid, DriftArgs a, const float4* start,
                         const float4* direction, float4* positions);

}  // namespace masav::cuda::launch
