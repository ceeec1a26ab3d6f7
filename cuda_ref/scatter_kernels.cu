// scatter_table: one photon per thread (engine/kernels/scatter_math.h with T = float); one tau row
// per block; fixed-point tallies in shared memory, then 64-bit integer atomics per block, so the
// sums do not depend on the order of the atomics.
#include "cuda_ref/atom_launch.h"
#include "engine/kernels/scatter_math.h"

namespace masav::cuda::launch {
namespace {

__global__ void scatter_kernel(ScatterTableParams p, uint32_t blocks_per_row,
                               unsigned long long* tallies, uint32_t* hits) {
  extern __shared__ uint32_t smem[];
  const uint32_t entries = p.bins + kScatterExtras;
  uint32_t* s_weight = smem;
  uint32_t* s_hits = smem + entries;
  for (uint32_t e = threadIdx.x; e < entries; e += blockDim.x) s_weight[e] = s_hits[e] = 0;
  __syncthreads();
  const uint32_t block = blockIdx.x + blockIdx.y * gridDim.x;
  const uint32_t row = block / blocks_per_row;
  const uint32_t photon = (block % blocks_per_row) * blockDim.x + threadIdx.x;
  if (row < p.rows && photon < p.photons_per_row) {
    const float tau = float(p.first_row + row) * p.tau_step;
    const auto o = scatter::trace_photon<float>(p, tau, scatter::photon_stream(p, row, photon));
    const uint32_t fw = scatter::fixed_weight(o.weight);
    atomicAdd(&s_weight[o.entry], fw);
    atomicAdd(&s_hits[o.entry], 1u);
    if (o.entry < p.bins && o.scatterings == 0) {
      atomicAdd(&s_weight[p.bins + kScatterUnscattered], fw);
      atomicAdd(&s_hits[p.bins + kScatterUnscattered], 1u);
    }
  }
  __syncthreads();
  if (row >= p.rows) return;
  for (uint32_t e = threadIdx.x; e < entries; e += blockDim.x) {
    if (s_hits[e] == 0) continue;
    atomicAdd(&tallies[row * entries + e], (unsigned long long)s_weight[e]);
    atomicAdd(&hits[row * entries + e], s_hits[e]);
  }
}

__global__ void finalize_kernel(ScatterFinalizeParams p, const unsigned long long* tallies,
                                float* table) {
  const uint64_t i = (uint64_t(blockIdx.y) * gridDim.x + blockIdx.x) * blockDim.x + threadIdx.x;
  if (i < p.entries) table[i] = float(double(tallies[i]) * double(p.scale));
}

}  // namespace

cudaError_t scatter_table(cudaStream_t s, dim3 grid, uint32_t threads, const ScatterTableParams& p,
                          uint32_t blocks_per_row, unsigned long long* tallies, uint32_t* hits) {
  const size_t shared = 2 * size_t(p.bins + kScatterExtras) * sizeof(uint32_t);
  scatter_kernel<<<grid, threads, shared, s>>>(p, blocks_per_row, tallies, hits);
  return cudaGetLastError();
}

cudaError_t scatter_finalize(cudaStream_t s, dim3 grid, const ScatterFinalizeParams& p,
                             const unsigned long long* tallies, float* table) {
  finalize_kernel<<<grid, 256, 0, s>>>(p, tallies, table);
  return cudaGetLastError();
}

}  // namespace masav::cuda::launch
