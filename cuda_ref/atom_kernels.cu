// Electron cloud and nebula lighting: thin launches around engine/kernels/orbital_math.h and
// nebula_math.h, the very functions the CPU reference runs (here with T = float).
#include "cuda_ref/atom_launch.h"
#include "cuda_ref/cuda_launch.h"
#include "engine/kernels/nebula_math.h"
#include "engine/kernels/orbital_math.h"

namespace masav::cuda::launch {
namespace {

__device__ uint64_t flat_thread() {
  return (uint64_t(blockIdx.y) * gridDim.x + blockIdx.x) * blockDim.x + threadIdx.x;
}

__global__ void orbital_kernel(OrbitalSampleParams p, const uint32_t* tables, float4* out) {
  const uint64_t i = flat_thread();
  if (i >= p.count) return;
  const hd::V3<float> x = orbital::sample_particle<float>(p, tables, uint32_t(i));
  out[i] = make_float4(x.x, x.y, x.z, 0.0f);
}

__global__ void density_kernel(const uint32_t* start, const uint32_t* end, uint32_t cells,
                               float scale, float* out) {
  const uint64_t c = flat_thread();
  if (c < cells) out[c] = float(end[c] - start[c]) * scale;
}

__global__ void illuminate_kernel(NebulaLightParams p, const float4* pos, const float* density,
                                  float* out) {
  const uint64_t i = flat_thread();
  if (i >= p.grid.n) return;
  const float4 x = pos[i];
  auto at = [density](uint32_t id) { return density[id]; };
  out[i] = nebula::illumination<float>(p, hd::V3<float>{x.x, x.y, x.z}, at);
}

__global__ void view_kernel(NebulaLightParams p, const float4* pos, const float* density,
                            const float* table, const float* illum, float* out) {
  const uint64_t i = flat_thread();
  if (i >= p.grid.n) return;
  const float4 x = pos[i];
  auto dat = [density](uint32_t id) { return density[id]; };
  auto tat = [table](uint32_t k) { return table[k]; };
  out[i] = nebula::view_light<float>(p, hd::V3<float>{x.x, x.y, x.z}, illum[i], dat, tat);
}

}  // namespace

cudaError_t orbital_sample(cudaStream_t s, dim3 grid, const OrbitalSampleParams& p,
                           const uint32_t* tables, float4* out) {
  orbital_kernel<<<grid, kBlock, 0, s>>>(p, tables, out);
  return cudaGetLastError();
}

cudaError_t cloud_density(cudaStream_t s, dim3 grid, const uint32_t* start, const uint32_t* end,
                          uint32_t cells, float scale, float* out) {
  density_kernel<<<grid, kBlock, 0, s>>>(start, end, cells, scale, out);
  return cudaGetLastError();
}

cudaError_t nebula_illuminate(cudaStream_t s, dim3 grid, const NebulaLightParams& p,
                              const float4* pos, const float* density, float* out) {
  illuminate_kernel<<<grid, kBlock, 0, s>>>(p, pos, density, out);
  return cudaGetLastError();
}

cudaError_t nebula_view(cudaStream_t s, dim3 grid, const NebulaLightParams& p, const float4* pos,
                        const float* density, const float* table, const float* illumination,
                        float* out) {
  view_kernel<<<grid, kBlock, 0, s>>>(p, pos, density, table, illumination, out);
  return cudaGetLastError();
}

}  // namespace masav::cuda::launch
