#pragma once
// The .cu side of the CUDA SPH kernels: launchers around sph_kernels.cu, returning the launch
// status; the host code (cuda_sph.cpp) checks it. Stats words: engine/sph/sph_kernel_params.h.
#include <cuda_runtime_api.h>

#include <cstdint>

#include "engine/kernels/sph_kernels.h"

namespace masav::cuda::launch {

struct SphGridArgs {
  uint32_t dims[3];
  uint32_t n;
  uint32_t max_candidates;
};

cudaError_t sph_density(cudaStream_t s, dim3 grid, SphGridArgs g, sph::Coefficients<float> c,
                        const float4* pos, const uint32_t* cells, const uint32_t* start,
                        const uint32_t* end, float* density, float* pressure, uint32_t* stats);

cudaError_t sph_forces(cudaStream_t s, dim3 grid, SphGridArgs g, sph::Coefficients<float> c,
                       const float4* pos, const float4* vel, const float* density,
                       const float* pressure, const uint32_t* cells, const uint32_t* start,
                       const uint32_t* end, float4* accel, uint32_t* stats);

struct SphIntegrateArgs {
  sph::StageParams<float> stage;
  uint32_t n;
};
// x0/x_out unused (may be null) for the kick; vk null: the stage velocity is v0.
cudaError_t sph_integrate(cudaStream_t s, dim3 grid, SphIntegrateArgs a, const float4* x0,
                          const float4* v0, const float4* vk, const float4* accel, float4* x_out,
                          float4* v_out, float4* sum_x, float4* sum_v, uint32_t* stats);

}  // namespace masav::cuda::launch
