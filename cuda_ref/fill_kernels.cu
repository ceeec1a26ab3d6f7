// The fill kernel behind DeviceApi::fill (the Philox kernels run their shared bodies,
// engine/kernels/random_body.h).
#include "cuda_ref/cuda_launch.h"

namespace masav::cuda::launch {
namespace {

__global__ void fill_kernel(uint32_t* dst, size_t words, uint32_t value) {
  const uint64_t i = (uint64_t(blockIdx.y) * gridDim.x + blockIdx.x) * blockDim.x + threadIdx.x;
  if (i < words) dst[i] = value;
}

}  // namespace

cudaError_t fill_u32(cudaStream_t s, dim3 grid, uint32_t* dst, size_t words, uint32_t value) {
  fill_kernel<<<grid, kBlock, 0, s>>>(dst, words, value);
  return cudaGetLastError();
}

}  // namespace masav::cuda::launch
