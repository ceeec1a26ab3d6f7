#pragma once
// What the CUDA particle kernels share (sph_kernels.cu, dfsph_kernels.cu): one thread per
// particle over a 2-D grid of blocks, and the warp reductions behind their one atomic per warp.
#include <cstdint>

namespace masav::cuda::launch {

__device__ inline uint64_t particle_thread() {
  return (uint64_t(blockIdx.y) * gridDim.x + blockIdx.x) * blockDim.x + threadIdx.x;
}

__device__ inline uint32_t warp_max(uint32_t v) {
  for (int o = 16; o > 0; o >>= 1) v = max(v, __shfl_xor_sync(0xffffffffu, v, o));
  return v;
}
__device__ inline uint32_t warp_sum(uint32_t v) {
  for (int o = 16; o > 0; o >>= 1) v += __shfl_xor_sync(0xffffffffu, v, o);
  return v;
}
__device__ inline bool lane0() {
  return (threadIdx.x & 31u) == 0u;
}

}  // namespace masav::cuda::launch
