#pragma once
// Buffers and their memory. One allocation per buffer (the engine allocates few, large buffers).
// Allocations are shared_ptr so that recorded work keeps them alive until its fence signals.
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "compute/device/vk_context.h"
#include "engine/core/buffer.h"

namespace masav::vk {

enum class MemoryUse {
  device,    // kernel data: device-local (and host-mapped on CPU and integrated devices)
  upload,    // staging for uploads: host-visible, coherent
  readback,  // staging for downloads and diagnostics: host-visible, cached where possible
};

struct Allocation {
  ::vk::raii::Buffer buffer = nullptr;
  ::vk::raii::DeviceMemory memory = nullptr;
  ::vk::DeviceSize bytes = 0;
  void* mapped = nullptr;  // non-null when host-visible
  bool coherent = true;
  std::string label;
  // Unique for the process's lifetime (addresses and handles of freed buffers are reused), so
  // that what was bound to it can be cached under it.
  uint64_t serial = 0;
  // Counts the commands recorded that write it (Stream::order) and the host's writes to its
  // mapping: what is derived from its contents (raymarch's quads) is current while this holds.
  mutable uint64_t writes = 0;
  // Views of the whole buffer as a uniform texel buffer, one per format asked for (texel_view).
  std::vector<std::pair<::vk::Format, ::vk::raii::BufferView>> views;
};

std::shared_ptr<Allocation> allocate(const Context& ctx, ::vk::DeviceSize bytes, MemoryUse use,
                                     const std::string& label);
// How a shader reads the buffer at a binding: as a storage buffer, or as a uniform texel buffer
// of one format (texelFetch, which lavapipe compiles to a gather rather than a per-lane loop).
struct Texels {
  ::vk::Format format = ::vk::Format::eUndefined;  // eUndefined: a storage buffer
  uint32_t bytes = 0;                              // per texel

  ::vk::DescriptorType descriptor_type() const {
    return format == ::vk::Format::eUndefined ? ::vk::DescriptorType::eStorageBuffer
                                              : ::vk::DescriptorType::eUniformTexelBuffer;
  }
};
// The formats the kernels and the renderer read: four floats, one float, one u32, four u32; and no
// texel buffer at all (a storage buffer).
inline constexpr Texels kTexelsRgba32f{::vk::Format::eR32G32B32A32Sfloat, 16};
inline constexpr Texels kTexelsR32f{::vk::Format::eR32Sfloat, 4};
inline constexpr Texels kTexelsR32u{::vk::Format::eR32Uint, 4};
inline constexpr Texels kTexelsRgba32u{::vk::Format::eR32G32B32A32Uint, 16};
inline constexpr Texels kStorageBuffer{};

// The buffer as a uniform texel buffer of `format` (`texel_bytes` per texel), made on first use
// and kept with the allocation. Throws, naming `kernel`, where the buffer holds more texels than
// the device's maxTexelBufferElements.
::vk::BufferView texel_view(const Context& ctx, Allocation& a, ::vk::Format format,
                            uint32_t texel_bytes, std::string_view kernel);
// Makes device writes to a non-coherent mapped allocation visible to the host.
void invalidate_for_host(const Context& ctx, const Allocation& a);

class VulkanBuffer final : public BufferImpl {
 public:
  VulkanBuffer(const DeviceApi* owner, ElemKind kind, size_t count, size_t bytes, std::string label,
               std::shared_ptr<Allocation> alloc)
      : BufferImpl(owner, kind, count, bytes, std::move(label)), alloc_(std::move(alloc)) {}
  const std::shared_ptr<Allocation>& alloc() const { return alloc_; }

 private:
  std::shared_ptr<Allocation> alloc_;
};

}  // namespace masav::vk
