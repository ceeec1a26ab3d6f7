#pragma once
// Launchers of the multi-pass atom kernels CUDA runs itself, scatter_table
// (scatter_kernels.cu) and voxelize (volume_kernels.cu); the host code in cuda_atom.cpp checks
// the returned status. The photons are the shared MASAV_HD math of engine/kernels/scatter_math.h
// with T = float.
#include <cuda_runtime_api.h>

#include <cstdint>

#include "engine/kernels/atom_params.h"

namespace masav::cuda::launch {

// One tau row per block of `threads` photons; tallies: 64-bit fixed-point weights per entry.
cudaError_t scatter_table(cudaStream_t s, dim3 grid, uint32_t threads, const ScatterTableParams& p,
                          uint32_t blocks_per_row, unsigned long long* tallies, uint32_t* hits);
cudaError_t scatter_finalize(cudaStream_t s, dim3 grid, const ScatterFinalizeParams& p,
                             const unsigned long long* tallies, float* table);

// tallies: count (u32) per cell, then the largest count; sums: 64-bit fixed-point light per cell.
cudaError_t voxelize_accumulate(cudaStream_t s, dim3 grid, const VoxelizeParams& p,
                                const float4* pos, const float* light, uint32_t* counts,
                                unsigned long long* sums);
cudaError_t voxelize_finalize(cudaStream_t s, dim3 grid, const VoxelizeParams& p,
                              const uint32_t* counts, const unsigned long long* sums, float* prob,
                              float* mean, float* sample);

}  // namespace masav::cuda::launch
