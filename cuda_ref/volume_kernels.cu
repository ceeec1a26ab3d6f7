// Voxelization, brick ranges and ray casting: thin launches around engine/kernels/volume_math.h
// (T = float) and the hash grid's fp32 cell rule.
#include "cuda_ref/atom_launch.h"
#include "cuda_ref/cuda_launch.h"
#include "engine/kernels/volume_math.h"
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

__global__ void bricks_kernel(VolumeBrickParams p, const float* vol, const float4* tf,
                              float4* bricks) {
  const uint64_t id = flat_thread();
  const uint32_t B = p.brick;
  const uint32_t dx = p.volume.dims.x, dy = p.volume.dims.y, dz = p.volume.dims.z;
  const uint32_t nx = (dx + B - 1) / B, ny = (dy + B - 1) / B, nz = (dz + B - 1) / B;
  if (id >= uint64_t(nx) * ny * nz) return;
  const uint32_t bx = uint32_t(id % nx), by = uint32_t(id / nx % ny), bz = uint32_t(id / (nx * ny));
  float lo = 3.0e38f, hi = -3.0e38f;
  for (uint32_t k = bz * B; k <= min((bz + 1) * B, dz - 1); ++k)
    for (uint32_t j = by * B; j <= min((by + 1) * B, dy - 1); ++j)
      for (uint32_t i = bx * B; i <= min((bx + 1) * B, dx - 1); ++i) {
        const float v = vol[(size_t(k) * dy + j) * dx + i];
        lo = fminf(lo, v);
        hi = fmaxf(hi, v);
      }
  const float scale = 1.0f / (p.volume.value_max - p.volume.value_min);
  const float nlo = fminf(1.0f, fmaxf(0.0f, (lo - p.volume.value_min) * scale));
  const float nhi = fminf(1.0f, fmaxf(0.0f, (hi - p.volume.value_min) * scale));
  const uint32_t k0 = uint32_t(nlo * float(p.tf_size - 1));
  const uint32_t k1 = min(uint32_t(ceilf(nhi * float(p.tf_size - 1))), p.tf_size - 1);
  float amax = 0.0f;
  for (uint32_t k = k0; k <= k1; ++k) amax = fmaxf(amax, tf[k].w);
  bricks[id] = make_float4(lo, hi, amax, 0.0f);
}

__global__ void raymarch_kernel(RaymarchParams p, volume::RayCamera cam, const float* vol,
                                const float4* tf, const float4* bricks, float4* image) {
  const uint64_t id = flat_thread();
  if (id >= uint64_t(p.width) * p.height) return;
  const uint32_t dx = p.volume.dims.x, dy = p.volume.dims.y;
  auto vat = [vol, dx, dy](uint32_t i, uint32_t j, uint32_t k) {
    return vol[(size_t(k) * dy + j) * dx + i];
  };
  auto tat = [tf](uint32_t k) {
    const float4 c = tf[k];
    return volume::V4<float>{c.x, c.y, c.z, c.w};
  };
  auto bat = [bricks, &cam](uint32_t x, uint32_t y, uint32_t z) {
    return bricks[(size_t(z) * cam.bricks[1] + y) * cam.bricks[0] + x].z;
  };
  const auto c = volume::raymarch_pixel<float>(p, cam, uint32_t(id % p.width),
                                               uint32_t(id / p.width), vat, tat, bat);
  image[id] = make_float4(c.r, c.g, c.b, c.a);
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

cudaError_t volume_bricks(cudaStream_t s, dim3 grid, const VolumeBrickParams& p, const float* vol,
                          const float4* tf, float4* bricks) {
  bricks_kernel<<<grid, kBlock, 0, s>>>(p, vol, tf, bricks);
  return cudaGetLastError();
}

cudaError_t raymarch(cudaStream_t s, dim3 grid, const RaymarchParams& p,
                     const volume::RayCamera& cam, const float* vol, const float4* tf,
                     const float4* bricks, float4* image) {
  raymarch_kernel<<<grid, kBlock, 0, s>>>(p, cam, vol, tf, bricks, image);
  return cudaGetLastError();
}

}  // namespace masav::cuda::launch
