#pragma once
// The CPU reference's path for every kernel with a shared body (engine/kernels/kernel_body.h):
// invocation i is KernelBody<K>::run<double>(i, ...) on the thread pool, its Real buffers in
// double. Included by cpu_kernels.cpp, where the kernels are expanded from kernels.inc.
#include <atomic>
#include <tuple>

#include "engine/cpu/cpu_backend.h"
#include "engine/kernels/kernel_body.h"
#include "engine/kernels/kernel_checks.h"

namespace masav::cpu {

// Diagnostics of one call: the flags raised, and the smallest index that raised one.
class CpuDiag {
 public:
  void report(uint32_t flag, uint32_t index) {
    flags_.fetch_or(flag);
    uint32_t seen = detail_.load();
    while (index < seen && !detail_.compare_exchange_weak(seen, index)) {
    }
  }
  uint32_t flags() const { return flags_.load(); }
  uint32_t detail() const { return detail_.load(); }

 private:
  std::atomic<uint32_t> flags_{0}, detail_{UINT32_MAX};
};

// The address of a CPU buffer's storage, and the pointer a body gets for a buffer argument.
inline void* cpu_data(const BufferImpl& b) {
  return const_cast<std::byte*>(static_cast<const CpuBuffer&>(b).data());
}
template <class B>
auto body_pointer(B& b) {
  return masav::body_pointer<double>(cpu_data, b);
}

// Invocations [0, items) of kernel K's body on `pool`, then its diagnostics raised as an Error.
template <KernelId K, class Params, class... Buffers>
void run_shared_body(const Backend& backend, ThreadPool& pool, const Params& p, uint64_t items,
                     Buffers&... buffers) {
  using Body = KernelBody<K>;
  const auto& layout = device_params<double>(p, buffers...);
  const auto ptrs = std::make_tuple(body_pointer(buffers)...);
  CpuDiag diag;
  pool.parallel_for(items, Body::kCpuGrain, [&](size_t b, size_t e) {
    std::apply(
        [&](auto*... q) {
          for (size_t i = b; i < e; ++i)
            Body::template run<double>(uint32_t(i), layout, diag, q...);
        },
        ptrs);
  });
  if (diag.flags()) {
    raise_diagnostics(backend, diag.flags(), diag.detail(), diag_limit(layout));
  }
}

}  // namespace masav::cpu
