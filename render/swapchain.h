#pragma once
// The window's swapchain: each frame is drawn offscreen like a headless frame and blitted into
// the acquired swapchain image, so the demo shows exactly what `masav run` writes.
#include <cstdint>
#include <vector>

#include "compute/device/vk_context.h"

namespace masav::render {

class Swapchain {
 public:
  // Takes ownership of `surface` (created by the window system for ctx's instance).
  Swapchain(const vk::Context& ctx, VkSurfaceKHR surface, uint32_t width, uint32_t height);
  ~Swapchain();

  // Rebuilds the swapchain for a new window size.
  void recreate(uint32_t width, uint32_t height);
  uint32_t width() const { return extent_.width; }
  uint32_t height() const { return extent_.height; }

  // Acquires the next image; false when the swapchain is out of date (recreate and retry).
  bool acquire();
  ::vk::Semaphore image_available() const { return *available_; }
  ::vk::Semaphore render_finished() const { return *finished_; }
  // Records the blit of `src` (TRANSFER_SRC layout) into the acquired image, ready to present.
  void record_blit(const ::vk::raii::CommandBuffer& cmd, ::vk::Image src, uint32_t src_w,
                   uint32_t src_h) const;
  // Presents the acquired image after render_finished(); false when out of date.
  bool present();

 private:
  void build(uint32_t width, uint32_t height);

  const vk::Context& ctx_;
  ::vk::raii::SurfaceKHR surface_ = nullptr;
  ::vk::raii::SwapchainKHR swapchain_ = nullptr;
  std::vector<::vk::Image> images_;
  ::vk::Format format_ = ::vk::Format::eUndefined;
  ::vk::Extent2D extent_;
  ::vk::raii::Semaphore available_ = nullptr, finished_ = nullptr;
  uint32_t index_ = 0;
};

}  // namespace masav::render
