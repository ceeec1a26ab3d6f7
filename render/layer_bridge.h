#pragma once
// Hands the compute backend's buffers to the renderer. On the renderer's own Vulkan device the
// kernel's allocation is bound as it is (no copy); from CUDA or the CPU reference the buffer is
// downloaded and uploaded into the renderer's memory -- only when the layer's version changed,
// so a paused scene or an unchanged background costs nothing per frame. Reals arrive as fp32.
#include <map>
#include <memory>
#include <string>

#include "compute/device/vk_memory.h"
#include "engine/kernels/backend.h"
#include "render/render_device.h"

namespace masav::render {

class LayerBridge {
 public:
  explicit LayerBridge(const RenderDevice& dev) : dev_(dev) {}

  // `slot` names the role ("positions", "scalars", "background"); one cached copy per slot.
  // vec4 positions (count of them), fp32.
  std::shared_ptr<vk::Allocation> positions(const std::string& slot, const Buffer<Real4>& b,
                                            uint32_t count, uint64_t version);
  // 32-bit words: u32 and f32 buffers as they are, real buffers converted to f32.
  std::shared_ptr<vk::Allocation> words(const std::string& slot, const BufferImpl& b,
                                        uint64_t version);
  // Bytes copied from the compute backend so far (0 when it shares the device).
  uint64_t bytes_copied() const { return bytes_copied_; }

 private:
  struct Slot {
    const BufferImpl* source = nullptr;
    uint64_t version = 0;
    std::shared_ptr<vk::Allocation> copy;
  };
  std::shared_ptr<vk::Allocation> store(const std::string& slot, const BufferImpl& src,
                                        uint64_t version, const void* data, size_t bytes);
  bool fresh(const std::string& slot, const BufferImpl& src, uint64_t version) const;

  const RenderDevice& dev_;
  std::map<std::string, Slot> slots_;
  uint64_t bytes_copied_ = 0;
};

}  // namespace masav::render
