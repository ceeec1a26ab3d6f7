#pragma once
// What a backend can hand to other Vulkan code without a copy. The renderer asks the compute
// backend for it (Backend::vulkan_interop) instead of knowing which backend it holds: a backend
// that computes on a Vulkan device hands over that device and the allocation behind each of its
// buffers, so kernel outputs are drawn where they lie. The types are the Vulkan device
// library's (compute/device/), declared here only.
#include <memory>

#include "engine/core/buffer.h"

namespace masav::vk {
class Context;
struct Allocation;
}  // namespace masav::vk

namespace masav {

class VulkanInterop {
 public:
  // The device the backend computes on.
  virtual const vk::Context& vulkan_context() const = 0;
  // The allocation behind one of the backend's buffers (an Error if it is another's).
  virtual std::shared_ptr<vk::Allocation> vulkan_buffer(const BufferImpl& b) const = 0;

 protected:
  ~VulkanInterop() = default;
};

}  // namespace masav
