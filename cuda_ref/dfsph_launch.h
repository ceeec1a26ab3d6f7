#pragma once
// The .cu side of the CUDA DFSPH kernels: launchers around dfsph_kernels.cu, returning the
// launch status; the host code (cuda_dfsph.cpp) checks it. neighbor_rows may be null, and so
// may dfsph_correct's residual where the layout's stop_slot is kDfsphNoStop.
#include <cuda_runtime_api.h>

#include <cstdint>

#include "engine/core/hd.h"
#include "engine/kernels/dfsph_params.h"

namespace masav::cuda::launch {

cudaError_t dfsph_factor(cudaStream_t s, dim3 grid, const DfsphLayout<float>& c,
                         const hd::V4<float>* pos, const uint32_t* cells, const uint32_t* start,
                         const uint32_t* end, float* factor, uint32_t* stats,
                         const uint32_t* neighbor_rows);

cudaError_t dfsph_rate(cudaStream_t s, dim3 grid, const DfsphLayout<float>& c,
                       const hd::V4<float>* pos, const hd::V4<float>* vel, const float* density,
                       const float* factor, const uint32_t* cells, const uint32_t* start,
                       const uint32_t* end, float* kappa, float* kappa_sum, uint32_t* residual,
                       const uint32_t* neighbor_rows);

cudaError_t dfsph_correct(cudaStream_t s, dim3 grid, const DfsphLayout<float>& c,
                          const hd::V4<float>* pos, const float* kappa, const uint32_t* cells,
                          const uint32_t* start, const uint32_t* end, hd::V4<float>* vel,
                          uint32_t* stats, const uint32_t* residual, const uint32_t* neighbor_rows);

}  // namespace masav::cuda::launch
