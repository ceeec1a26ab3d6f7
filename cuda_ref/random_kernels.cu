// Philox and fill kernels: thin wrappers around engine/kernels/philox.h.
#include "cuda_ref/cuda_launch.h"
#include "engine/kernels/philox.h"

namespace masav::cuda::launch {
namespace {

__device__ uint64_t flat_thread() {
  return (uint64_t(blockIdx.y) * gridDim.x + blockIdx.x) * blockDim.x + threadIdx.x;
}

__global__ void philox_kernel(uint64_t seed, uint64_t stream, uint64_t first_block, uint32_t count,
                              bool uniform, uint32_t* out) {
  const uint64_t block = flat_thread();
  if (block >= (uint64_t(count) + 3) / 4) return;
  const philox::Block r = philox::stream_block(seed, stream, first_block + block);
  for (uint32_t j = 0; j < 4; ++j) {
    const uint64_t i = 4 * block + j;
    if (i < count) out[i] = uniform ? __float_as_uint(philox::u01(r.w[j])) : r.w[j];
  }
}

__global__ void fill_kernel(uint32_t* dst, size_t words, uint32_t value) {
  const uint64_t i = flat_thread();
  if (i < words) dst[i] = value;
}

}  // namespace

cudaError_t philox(cudaStream_t s, dim3 grid, uint64_t seed, uint64_t stream,
                   uint64_t first_block, uint32_t count, bool uniform, uint32_t* out) {
  philox_kernel<<<grid, kBlock, 0, s>>>(seed, stream, first_block, count, uniform, out);
  return cudaGetLastError();
}

cudaError_t fill_u32(cudaStream_t s, dim3 grid, uint32_t* dst, size_t words, uint32_t value) {
  fill_kernel<<<grid, kBlock, 0, s>>>(dst, words, value);
  return cudaGetLastError();
}

}  // namespace masav::cuda::launch
