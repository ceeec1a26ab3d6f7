#pragma once
// CUDA's path for every kernel with a shared body (engine/kernels/kernel_body.h): one thread per
// invocation runs KernelBody<K>::run<float>, the code the CPU reference runs in double. Included
// only by cuda_kernels.cu, where the kernels are expanded from kernels.inc.
#include "cuda_ref/cuda_launch.h"
#include "engine/kernels/kernel_body.h"

namespace masav::cuda {

// Diagnostics words on the device: {max_loop_ticks, flags, detail, reserved}.
struct CudaDiag {
  uint32_t* words;
  __device__ void report(uint32_t flag, uint32_t index) {
    atomicOr(&words[1], flag);
    atomicMin(&words[2], index);
  }
};

// Blocks of launch::kBlock threads per multiprocessor the compiler must fit: a body's
// kCudaMinBlocks where it names one (as kCpuGrain tunes the CPU reference), else 1 (no bound).
template <KernelId K>
constexpr int kMinBlocks = [] {
  if constexpr (requires { KernelBody<K>::kCudaMinBlocks; })
    return int(KernelBody<K>::kCudaMinBlocks);
  else
    return 1;
}();

template <KernelId K, class Layout, class... Pointers>
__global__ void __launch_bounds__(launch::kBlock, kMinBlocks<K>)
    shared_body_kernel(uint64_t items, Layout layout, uint32_t* diag_words, Pointers... pointers) {
  const uint64_t i = (uint64_t(blockIdx.y) * gridDim.x + blockIdx.x) * blockDim.x + threadIdx.x;
  if (i >= items) return;
  CudaDiag diag{diag_words};
  KernelBody<K>::template run<float>(uint32_t(i), layout, diag, pointers...);
}

// The device address of a CUDA buffer, and the pointer a body gets for a buffer argument.
inline void* cuda_data(const BufferImpl& b) {
  return static_cast<const CudaBuffer&>(b).ptr();
}
template <class B>
auto body_pointer(B& b) {
  return masav::body_pointer<float>(cuda_data, b);
}

}  // namespace masav::cuda
