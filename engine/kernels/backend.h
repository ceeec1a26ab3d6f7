#pragma once
// The kernel set as an interface. Each kernel of engine/kernels/kernels.inc becomes
//   - a public non-virtual method, Backend::name(p, buffers...), which enforces the contract
//     once for every backend: the buffers belong to this backend, the parameters pass the
//     kernel's validate() (same message everywhere), empty work returns before any backend code,
//     the kernel's device time is recorded when asked, and a fault is injected when armed;
//   - a protected pure virtual do_name(p, items, buffers...), which each backend implements
//     (declared in one line with MASAV_KERNEL_OVERRIDE), so a kernel missing from one backend
//     is a build error.
// Buffers, ordering and timestamps are in device_api.h.
#include <optional>
#include <span>
#include <string_view>
#include <type_traits>
#include <vector>

#include "engine/core/device_api.h"
#include "engine/core/interop.h"
#include "engine/core/tuning.h"
#include "engine/kernels/kernel_id.h"
#include "engine/kernels/kernel_macros.h"
#define MASAV_KERNEL_PARAMS
#include "engine/kernels/kernels.inc"
#undef MASAV_KERNEL_PARAMS

namespace masav {

// A kernel call's arguments, named as in kernels.inc (a.p, a.items_, a.positions, ...).
template <KernelId K>
struct KernelArgs;
#define MASAV_KERNEL MASAV_KERNEL_ARGS
#include "engine/kernels/kernels.inc"
#undef MASAV_KERNEL

// The device time one kernel call took (Backend::set_kernel_timing).
struct KernelTiming {
  KernelId kernel;
  TimestampId begin, end;  // DeviceApi::timestamp_ns() of each, valid after finish()
};

class Backend : public DeviceApi {
 public:
#define MASAV_KERNEL(name, Params, items, ...)                                       \
  void name(const Params& p MASAV_BUFFER_PARAMS(__VA_ARGS__)) {                      \
    static constexpr const char* kBufferNames[] = {MASAV_BUFFER_NAMES(__VA_ARGS__)}; \
    enforce(                                                                         \
        KernelId::name, p, kBufferNames, [&] { return uint64_t(items); },            \
        [&](uint64_t n) {                                                            \
          do_##name(p, n MASAV_BUFFER_ARGS(__VA_ARGS__));                            \
        } MASAV_BUFFER_ARGS(__VA_ARGS__));                                           \
  }
#include "engine/kernels/kernels.inc"
#undef MASAV_KERNEL

  // Record each kernel's device time from now on (off by default: two timestamps per call).
  void set_kernel_timing(bool on) {
    kernel_timing_ = on;
  }
  // Calls recorded since the last take, in call order; read their times after finish().
  std::vector<KernelTiming> take_kernel_timings();

  // The tuning options the backend was created with (BackendRequest::tuning). Each backend
  // reads its own part; the SPH simulation its `sph` part; a cross-check's reference backend is
  // created with the same.
  const Tuning& tuning() const {
    return tuning_;
  }

  // What the backend hands other Vulkan code without a copy (null: it computes elsewhere).
  virtual const VulkanInterop* vulkan_interop() const {
    return nullptr;
  }

  // The most loop iterations any shader invocation ran since the last call, on a backend created
  // to count them (BackendRequest::count_loop_ticks); nothing elsewhere. The tests drive each
  // kernel's worst case with it against Capabilities::max_loop_iterations.
  virtual std::optional<uint32_t> take_max_loop_ticks() {
    return std::nullopt;
  }

  // Test hook: perturb the first output of every later call of `kernel` (one word flipped, or
  // one value changed by 1e-3 relative), so a cross-check can prove it catches a mismatch.
  void inject_fault(std::optional<KernelId> kernel) {
    fault_ = kernel;
  }

 protected:
  Tuning tuning_;

#define MASAV_KERNEL(name, Params, items, ...) \
  virtual void do_##name(const Params& p, uint64_t items_ MASAV_BUFFER_PARAMS(__VA_ARGS__)) = 0;
#include "engine/kernels/kernels.inc"
#undef MASAV_KERNEL

 private:
  template <class Params, size_t N, class Items, class Run, class... Buffers>
  void enforce(KernelId id, const Params& p, const char* const (&names)[N], Items items, Run run,
               Buffers&... buffers) {
    static_assert(N == sizeof...(Buffers));
    const BufferImpl* const impls[] = {impl_of(buffers)...};
    const bool required[] = {!std::is_pointer_v<Buffers>...};
    check_buffers(id, impls, names, required);
    validate(*this, p, buffers...);
    const uint64_t n = items();
    if (n == 0) return;
    const TimestampId begin = kernel_timing_ ? timestamp() : 0;
    run(n);
    if (kernel_timing_) timings_.push_back({id, begin, timestamp()});
    if (fault_ == id) perturb(first_output(buffers...));
  }

  // The first buffer the kernel writes (a non-const argument), or null.
  static BufferImpl* first_output() {
    return nullptr;
  }
  template <class T, class... Rest>
  static BufferImpl* first_output(T& b, Rest&... rest) {
    if constexpr (std::is_const_v<T>) {
      return first_output(rest...);
    } else if constexpr (std::is_same_v<T, BufferImpl>) {
      return &b;
    } else if constexpr (std::is_pointer_v<T>) {
      if constexpr (!std::is_const_v<std::remove_pointer_t<T>>)
        if (b && b->valid()) return &b->impl();
      return first_output(rest...);
    } else {
      return b.valid() ? &b.impl() : first_output(rest...);
    }
  }

  // Every required buffer allocated, every buffer this backend's own.
  void check_buffers(KernelId id, std::span<const BufferImpl* const> impls,
                     std::span<const char* const> names, std::span<const bool> required) const;
  void perturb(BufferImpl* out);

  bool kernel_timing_ = false;
  std::vector<KernelTiming> timings_;
  std::optional<KernelId> fault_;
};

}  // namespace masav
