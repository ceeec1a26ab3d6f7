#pragma once
// How the Vulkan backend binds each kernel's buffers, generated from the binding kind that every
// buffer entry of engine/kernels/kernels.inc carries. A kernel run as one dispatch of
// shaders/<name>.comp (vk_kernels.cpp) gets its descriptor set layout and its texel views from
// this table alone (dispatch_kernel -> Pipelines::get, Stream's descriptor sets);
// tests/test_vk_bindings.cpp checks the table against each shader's SPIR-V.
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <type_traits>
#include <vector>

#include "compute/device/vk_memory.h"
#include "engine/core/types.h"
#include "engine/kernels/kernel_id.h"
#include "engine/kernels/kernel_macros.h"

namespace masav::vk {

enum class BindingKind : uint8_t { storage, texel };

struct BufferBinding {
  BindingKind kind;
  // What is bound: a storage buffer, or texels of the element's format. An any_in buffer's
  // texels have no format here: its call picks one by the element size (gather, vk_grid.cpp).
  Texels texels;
};

// A buffer of Elem read as a uniform texel buffer: one texel per element (on Vulkan a Real is a
// float).
template <class Elem>
consteval Texels texels_of() {
  if constexpr (std::is_same_v<Elem, Real4>)
    return kTexelsRgba32f;
  else if constexpr (std::is_same_v<Elem, Real> || std::is_same_v<Elem, float>)
    return kTexelsR32f;
  else if constexpr (std::is_same_v<Elem, uint32_t>)
    return kTexelsR32u;
  else if constexpr (std::is_void_v<Elem>)
    return Texels{};  // any_in: per call
  else
    static_assert(std::is_void_v<Elem>, "kernels.inc: no texel format for this element type");
}

namespace bindings_detail {
#define MASAV_VK_BINDING_storage(elem)   \
  BufferBinding {                        \
    BindingKind::storage, kStorageBuffer \
  }
#define MASAV_VK_BINDING_texel(elem)      \
  BufferBinding {                         \
    BindingKind::texel, texels_of<elem>() \
  }
#define MASAV_VK_BINDING(binding, elem) MASAV_VK_BINDING_##binding(elem)
// One array per kernel, named after it: its buffers' bindings in the order of kernels.inc.
#define MASAV_KERNEL(name, Params, items, ...) \
  inline constexpr BufferBinding name[] = {MASAV_BUFFER_BINDINGS(MASAV_VK_BINDING, __VA_ARGS__)};
#include "engine/kernels/kernels.inc"
#undef MASAV_KERNEL
#undef MASAV_VK_BINDING
#undef MASAV_VK_BINDING_texel
#undef MASAV_VK_BINDING_storage
}  // namespace bindings_detail

// Each kernel's buffer bindings, by KernelId: bindings 1, 2, ... (binding 0 is the diagnostics
// word, shaders/common/kernel_base.glsl).
inline constexpr std::array<std::span<const BufferBinding>, kKernelCount> kKernelBindings = {
#define MASAV_KERNEL(name, ...) std::span<const BufferBinding>(bindings_detail::name),
#include "engine/kernels/kernels.inc"
#undef MASAV_KERNEL
};

constexpr std::span<const BufferBinding> kernel_bindings(KernelId k) {
  return kKernelBindings[size_t(k)];
}

// The one binding a kernel has after its buffers, a buffer of the backend's own that it reads,
// where it has one: raymarch's quads (VulkanBackend::raymarch_quads in vk_volume.cpp, the volume
// four voxels to an rgba32f texel; where it reads none, another of its buffers fills the
// binding), and sph_integrate's table of replayed values (Stream::value_table, its dt, a
// storage buffer).
constexpr std::optional<Texels> kernel_extra(KernelId k) {
  if (k == KernelId::raymarch) return kTexelsRgba32f;
  if (k == KernelId::sph_integrate) return kStorageBuffer;
  return std::nullopt;
}

// What a kernel run as one dispatch binds at 1, 2, ...: its buffers, then its extra.
inline std::vector<Texels> kernel_texels(KernelId k) {
  std::vector<Texels> t;
  for (const BufferBinding& b : kernel_bindings(k)) t.push_back(b.texels);
  if (const std::optional<Texels> extra = kernel_extra(k)) t.push_back(*extra);
  return t;
}

}  // namespace masav::vk
