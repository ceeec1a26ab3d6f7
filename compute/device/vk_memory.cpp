#include "compute/device/vk_memory.h"

#include <fmt/format.h>

#include <atomic>
#include <optional>

#include "engine/core/error.h"

namespace masav::vk {
namespace {

using MP = ::vk::MemoryPropertyFlagBits;

std::optional<uint32_t> find_type(const ::vk::PhysicalDeviceMemoryProperties& mem, uint32_t allowed,
                                  ::vk::MemoryPropertyFlags want) {
  for (uint32_t i = 0; i < mem.memoryTypeCount; ++i)
    if ((allowed & (1u << i)) && (mem.memoryTypes[i].propertyFlags & want) == want) return i;
  return std::nullopt;
}

}  // namespace

std::shared_ptr<Allocation> allocate(const Context& ctx, ::vk::DeviceSize bytes, MemoryUse use,
                                     const std::string& label) {
  static std::atomic<uint64_t> next_serial{1};
  auto a = std::make_shared<Allocation>();
  a->serial = next_serial.fetch_add(1, std::memory_order_relaxed);
  a->label = label;
  a->bytes = std::max<::vk::DeviceSize>(bytes, 16);  // Vulkan has no empty buffers
  using BU = ::vk::BufferUsageFlagBits;
  ::vk::BufferCreateInfo info(
      {}, a->bytes,
      BU::eStorageBuffer | BU::eUniformTexelBuffer | BU::eTransferSrc | BU::eTransferDst);
  try {
    a->buffer = ::vk::raii::Buffer(ctx.device(), info);
    const auto req = a->buffer.getMemoryRequirements();
    const auto mem = ctx.physical().getMemoryProperties();
    const bool unified = ctx.caps().device_type == "cpu" || ctx.caps().device_type == "integrated";
    std::optional<uint32_t> type;
    switch (use) {
      case MemoryUse::device:
        if (unified)
          type = find_type(mem, req.memoryTypeBits,
                           MP::eDeviceLocal | MP::eHostVisible | MP::eHostCoherent);
        if (!type) type = find_type(mem, req.memoryTypeBits, MP::eDeviceLocal);
        break;
      case MemoryUse::upload:
        type = find_type(mem, req.memoryTypeBits, MP::eHostVisible | MP::eHostCoherent);
        break;
      case MemoryUse::readback:
        type = find_type(mem, req.memoryTypeBits, MP::eHostVisible | MP::eHostCached);
        if (!type) type = find_type(mem, req.memoryTypeBits, MP::eHostVisible);
        break;
    }
    if (!type) type = find_type(mem, req.memoryTypeBits, {});
    if (!type)
      throw Error("vulkan", "allocate", fmt::format("no memory type for buffer '{}'", label),
                  "report this device; it offers no usable memory type");
    ::vk::MemoryAllocateInfo ainfo(req.size, *type);
    a->memory = ::vk::raii::DeviceMemory(ctx.device(), ainfo);
    a->buffer.bindMemory(*a->memory, 0);
    const auto flags = mem.memoryTypes[*type].propertyFlags;
    a->coherent = bool(flags & MP::eHostCoherent);
    if (flags & MP::eHostVisible) a->mapped = a->memory.mapMemory(0, VK_WHOLE_SIZE);
  } catch (const ::vk::OutOfDeviceMemoryError&) {
    throw Error("vulkan", "allocate",
                fmt::format("out of device memory for '{}' ({} MiB) on {}", label, bytes >> 20,
                            ctx.caps().device_name),
                "use fewer elements, or free other GPU work");
  } catch (const ::vk::OutOfHostMemoryError&) {
    throw Error("vulkan", "allocate",
                fmt::format("out of host memory for '{}' ({} MiB)", label, bytes >> 20),
                "use fewer elements");
  }
  return a;
}

::vk::BufferView texel_view(const Context& ctx, Allocation& a, ::vk::Format format,
                            uint32_t texel_bytes, std::string_view kernel) {
  for (const auto& [f, view] : a.views)
    if (f == format) return *view;
  const uint64_t texels = a.bytes / texel_bytes;
  if (texels > ctx.max_texel_buffer_elements())
    throw Error("vulkan", std::string(kernel),
                fmt::format("buffer '{}' holds {} texels; {} reads at most {} per buffer", a.label,
                            texels, ctx.caps().device_name, ctx.max_texel_buffer_elements()),
                "use fewer elements (voxels, particles), or --backend cpu or cuda");
  ::vk::BufferViewCreateInfo info({}, *a.buffer, format, 0, texels * texel_bytes);
  a.views.emplace_back(format, ::vk::raii::BufferView(ctx.device(), info));
  return *a.views.back().second;
}

void invalidate_for_host(const Context& ctx, const Allocation& a) {
  if (a.coherent || !a.mapped) return;
  ::vk::MappedMemoryRange range(*a.memory, 0, VK_WHOLE_SIZE);
  ctx.device().invalidateMappedMemoryRanges(range);
}

}  // namespace masav::vk
