#pragma once
// The .cu side of the CUDA SPH kernels: launchers around sph_kernels.cu, returning the launch
// status; the host code (cuda_sph.cpp) checks it. Stats words: engine/kernels/sph_kernel_params.h.
#include <cuda_runtime_api.h>

#include <cstdint>

#include "engine/core/hd.h"
#include "engine/kernels/sph_kernel_params.h"

namespace masav::cuda::launch {

using V4 = hd::V4<float>;

// neighbor_rows (the row masks, kSphRowMaskWords n words) may be null: none written / read.
// reach_rows likewise (written or read as c.reach says). images_after: sph::force_at's
// ImagesAfter (the wall images in a walk of their own after the direct terms). state, the
// neighbour state (kSphStateStride), may be null: not written (then vel is unread) / not read.
cudaError_t sph_density(cudaStream_t s, dim3 grid, const SphStepLayout<float>& c, const V4* pos,
                        const uint32_t* cells, const uint32_t* start, const uint32_t* end,
                        float* density, float* pressure, uint32_t* stats, const V4* vel, V4* state,
                        uint32_t* reach_rows, uint32_t* neighbor_rows);

cudaError_t sph_forces(cudaStream_t s, dim3 grid, const SphStepLayout<float>& c, const V4* pos,
                       const V4* vel, const float* density, const float* pressure, const V4* state,
                       const uint32_t* cells, const uint32_t* start, const uint32_t* end, V4* accel,
                       uint32_t* stats, const uint32_t* neighbor_rows, bool images_after);

// Buffers the stage does not use are null (see sph::integrate_particle).
cudaError_t sph_integrate(cudaStream_t s, dim3 grid, const SphIntegrateLayout<float>& p,
                          const V4* x0, const V4* v0, const V4* vk, const V4* accel, V4* x_out,
                          V4* v_out, V4* sum_x, V4* sum_v, uint32_t* stats);

}  // namespace masav::cuda::launch
