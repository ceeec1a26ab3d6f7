// Every kernel of engine/kernels/kernels.inc on the CPU reference: a kernel with a shared body runs
// it on the thread pool (cpu_elementwise.h); the others are the CPU reference's own run_own
// (cpu_sort.cpp, cpu_grid.cpp, cpu_sph.cpp, cpu_scatter.cpp, cpu_volume.cpp).
#include "engine/cpu/cpu_elementwise.h"
#define MASAV_KERNEL_BODIES
#include "engine/kernels/kernels.inc"
#undef MASAV_KERNEL_BODIES

namespace masav::cpu {

template <KernelId K, class Params, class... Buffers>
void CpuBackend::run_kernel(const Params& p, uint64_t items, Buffers&... buffers) {
  ++counters_.launches;  // one kernel call runs as one launch here, whatever its passes
  if constexpr (K == KernelId::raymarch) {
    if (render_ == CpuRenderPrecision::fp32) return raymarch_fp32(p, buffers...);
  }
  if constexpr (HasKernelBody<K>)
    run_shared_body<K>(*this, pool_, p, items, buffers...);
  else
    run_own(KernelArgs<K>{p, items, buffers...});
}

#define MASAV_KERNEL(name, Params, items, ...) \
  MASAV_KERNEL_FORWARD(CpuBackend, name, Params, __VA_ARGS__)
#include "engine/kernels/kernels.inc"
#undef MASAV_KERNEL

}  // namespace masav::cpu
