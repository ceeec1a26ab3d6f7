// voxelize on CUDA: per-particle integer tallies on the hash grid's fp32 cell rule, then one
// pass per cell (brick ranges and ray casting run their shared bodies,
// engine/kernels/atom_body.h).
#include "cuda_ref/atom_launch.h"
#include "cuda_ref/cuda_launch.h"
#include "engine/kernels/grid_cell.h"

namespace masav::cuda::launch {
namespace {

__device__ uint64_t flat_thread() {
  return (uint64_t(blockIdx.y) * gridDim.x + blockIdx.x) * blockDim.x + threadIdx.x;
}

__global__ void accumulate_kernel(VoxelizeParams p, const float4* pos, const float* light,
                                  uint32_t* counts, unsigned long long* sums) {
  const uint64_t i = flat_thread();
  if (i >= p.grid.n) return;
  const float origin[3] = {p.grid.origin.x, p.grid.origin.y, p.grid.origin.z};
  const uint32_t dims[3] = {p.grid.dims.x, p.grid.dims.y, p.grid.dims.z};
  const float4 x = pos[i];
  const grid::CellCoord c = grid::point_cell(x.x, x.y, x.z, origin, p.grid.inv_cell, dims);
  const uint32_t id = grid::cell_id(c.x, c.y, c.z, dims[1], dims[2]);
  const float v = fminf(1.0f, fmaxf(0.0f, light[i] * p.light_to_unit));
  const uint32_t n = atomicAdd(&counts[id], 1u) + 1u;
  atomicAdd(&sums[id], (unsigned long long)(uint32_t(v * 16777216.0f + 0.5f)));
  const uint32_t cells = dims[0] * dims[1] * dims[2];
  atomicMax(&counts[cells], n);
}

__global__ void finalize_kernel(VoxelizeParams p, const uint32_t* counts,
                                const unsigned long long* sums, float* prob, float* mean,
                                float* sample) {
  const uint64_t o = flat_thread();  // output x fastest; the grid's cell id is z fastest
  const uint32_t dx = p.grid.dims.x, dy = p.grid.dims.y, dz = p.grid.dims.z;
  const uint32_t cells = dx * dy * dz;
  if (o >= cells) return;
  const uint32_t x = uint32_t(o % dx), y = uint32_t(o / dx % dy), z = uint32_t(o / (dx * dy));
  const uint32_t c = (x * dy + y) * dz + z;
  const uint32_t n = counts[c];
  const float g = n ? float(double(sums[c]) / 16777216.0) / float(n) : 0.0f;
  prob[o] = float(n) / float(p.grid.n);
  mean[o] = g;
  sample[o] = p.s * g + p.t * float(n) / float(counts[cells]);
}

}  // namespace

cudaError_t voxelize_accumulate(cudaStream_t s, dim3 grid, const VoxelizeParams& p,
                                const float4* pos, const float* light, uint32_t* counts,
                                unsigned long long* sums) {
  accumulate_kernel<<<grid, kBlock, 0, s>>>(p, pos, light, counts, sums);
  return cudaGetLastError();
}

cudaError_t voxelize_finalize(cudaStream_t s, dim3 grid, const VoxelizeParams& p,
                              const uint32_t* counts, const unsigned long long* sums, float* prob,
                              float* mean, float* sample) {
  finalize_kernel<<<grid, kBlock, 0, s>>>(p, counts, sums, prob, mean, sample);
  return cudaGetLastError();
}

}  // namespace masav::cuda::launch
