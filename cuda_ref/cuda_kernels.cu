// Every kernel of engine/kernels/kernels.inc on CUDA: a kernel with a shared body runs it from one
// generic launcher (cuda_elementwise.cuh); the others are CUDA's own run_own (cuda_sort.cpp,
// cuda_grid.cpp, cuda_sph.cpp, cuda_atom.cpp).
#include "cuda_ref/cuda_backend.h"
#include "cuda_ref/cuda_check.h"
#include "cuda_ref/cuda_elementwise.cuh"
#include "cuda_ref/cuda_launch.h"
#define MASAV_KERNEL_BODIES
#include "engine/kernels/kernels.inc"
#undef MASAV_KERNEL_BODIES

namespace masav::cuda {

template <KernelId K, class Params, class... Buffers>
void CudaBackend::run_kernel(const Params& p, uint64_t items, Buffers&... buffers) {
  if constexpr (HasKernelBody<K>) {
    const auto layout = device_params<float>(p, buffers...);
    if (const uint32_t limit = diag_limit(layout)) pending_diag_limit_ = limit;
    const char* name = kernel_name(K).data();
    shared_body_kernel<K><<<grid_for_items(items, name), launch::kBlock, 0, stream_>>>(
        items, layout, diag_, body_pointer(buffers)...);
    launched(cudaGetLastError(), name);
  } else {
    run_own(KernelArgs<K>{p, items, buffers...});
  }
}

#define MASAV_KERNEL(name, Params, items, ...) \
  MASAV_KERNEL_FORWARD(CudaBackend, name, Params, __VA_ARGS__)
#include "engine/kernels/kernels.inc"
#undef MASAV_KERNEL

}  // namespace masav::cuda
