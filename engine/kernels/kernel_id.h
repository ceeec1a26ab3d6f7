#pragma once
// Kernels by identity rather than by name: KernelId is generated from engine/kernels/kernels.inc,
// so every registry keyed by it (cross-checks, a scene's kernel list, fault injection, shader
// names, loop-limit cases) can be checked for completeness at run time in one loop.
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>

namespace masav {

enum class KernelId : uint32_t {
#define MASAV_KERNEL(name, ...) name,
#include "engine/kernels/kernels.inc"
#undef MASAV_KERNEL
};

inline constexpr size_t kKernelCount = 0
#define MASAV_KERNEL(name, ...) +1
#include "engine/kernels/kernels.inc"
#undef MASAV_KERNEL
    ;

// Every kernel, in the order of kernels.inc.
inline constexpr std::array<KernelId, kKernelCount> kAllKernels = {
#define MASAV_KERNEL(name, ...) KernelId::name,
#include "engine/kernels/kernels.inc"
#undef MASAV_KERNEL
};

// The kernel's name as written in kernels.inc ("drift_points").
std::string_view kernel_name(KernelId id);
// The kernel of that name, if there is one.
std::optional<KernelId> find_kernel(std::string_view name);
// Every name, comma-separated: what an error about a kernel name offers instead.
std::string_view kernel_names_list();

// Selects a backend's implementation of one kernel by overload (see engine/cpu/cpu_backend.h).
template <KernelId K>
struct KernelTag {
  static constexpr KernelId id = K;
};

}  // namespace masav
