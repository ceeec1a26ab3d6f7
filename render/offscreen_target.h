#pragma once
// The image every frame is drawn into: RGBA8 colour and a depth buffer, readable back for PNGs
// and copied to the window's swapchain by the demo. Headless and windowed frames are drawn the
// same way.
#include <cstdint>
#include <memory>
#include <vector>

#include "compute/device/vk_memory.h"
#include "render/render_device.h"

namespace masav::render {

constexpr ::vk::Format kColorFormat = ::vk::Format::eR8G8B8A8Unorm;

// A colour-and-depth render pass compatible with every OffscreenTarget (pipelines are made once
// against it). The colour image ends in TRANSFER_SRC layout, ready for readback or a blit.
// The frame's render pass: cleared, or `continued` (loads what an earlier pass of the same frame
// drew; the fluid surface draws in three passes).
::vk::raii::RenderPass make_render_pass(const vk::Context& ctx, bool continued = false);

class OffscreenTarget {
 public:
  OffscreenTarget(const vk::Context& ctx, ::vk::RenderPass pass, uint32_t width, uint32_t height);

  uint32_t width() const { return width_; }
  uint32_t height() const { return height_; }
  ::vk::Framebuffer framebuffer() const { return *framebuffer_; }
  ::vk::Image color_image() const { return *color_.image; }

  // Records the copy of the colour image into host memory (after the render pass).
  void record_readback(const ::vk::raii::CommandBuffer& cmd);
  // RGBA8 rows, top first, after the frame that recorded the readback has been submitted.
  std::vector<uint8_t> pixels() const;

 private:
  const vk::Context& ctx_;
  uint32_t width_, height_;
  ImageMemory color_, depth_;
  ::vk::raii::Framebuffer framebuffer_ = nullptr;
  std::shared_ptr<vk::Allocation> readback_;
};

}  // namespace masav::render
