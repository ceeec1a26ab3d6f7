#pragma once
// Launchers of the electron-cloud, nebula and volume kernels (atom_kernels.cu,
// scatter_kernels.cu, volume_kernels.cu): kernels only; the host code in cuda_atom.cpp checks
// the returned status. Every kernel body is the shared MASAV_HD math of engine/atom/*_math.h
// with T = float.
#include <cuda_runtime_api.h>

#include <cstdint>

#include "engine/atom/atom_params.h"
#include "engine/kernels/volume_math.h"

namespace masav::cuda::launch {

cudaError_t orbital_sample(cudaStream_t s, dim3 grid, const OrbitalSampleParams& p,
                           const uint32_t* tables, float4* out);
cudaError_t cloud_density(cudaStream_t s, dim3 grid, const uint32_t* start, const uint32_t* end,
                          uint32_t cells, float scale, float* out);
cudaError_t nebula_illuminate(cudaStream_t s, dim3 grid, const NebulaLightParams& p,
                              const float4* pos, const float* density, float* out);
cudaError_t nebula_view(cudaStream_t s, dim3 grid, const NebulaLightParams& p, const float4* pos,
                        const float* density, const float* table, const float* illumination,
                        float* out);

// One tau row per block of `threads` photons; tallies: 64-bit fixed-point weights per entry.
cudaError_t scatter_table(cudaStream_t s, dim3 grid, uint32_t threads, const ScatterTableParams& p,
                          uint32_t blocks_per_row, unsigned long long* tallies, uint32_t* hits);
cudaError_t scatter_finalize(cudaStream_t s, dim3 grid, const unsigned long long* tallies,
                             uint32_t entries, double scale, float* table);

// tallies: count (u32) per cell, then the largest count; sums: 64-bit fixed-point light per cell.
cudaError_t voxelize_accumulate(cudaStream_t s, dim3 grid, const VoxelizeParams& p,
                                const float4* pos, const float* light, uint32_t* counts,
                                unsigned long long* sums);
cudaError_t voxelize_finalize(cudaStream_t s, dim3 grid, const VoxelizeParams& p,
                              const uint32_t* counts, const unsigned long long* sums, float* prob,
                              float* mean, float* sample);
cudaError_t volume_bricks(cudaStream_t s, dim3 grid, const VolumeBrickParams& p, const float* vol,
                          const float4* tf, float4* bricks);
cudaError_t raymarch(cudaStream_t s, dim3 grid, const RaymarchParams& p,
                     const volume::RayCamera& cam, const float* vol, const float4* tf,
                     const float4* bricks, float4* image);

}  // namespace masav::cuda::launch
