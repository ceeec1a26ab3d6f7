#include "render/swapchain.h"

#include <fmt/format.h>

#include <algorithm>

#include "engine/core/error.h"

namespace masav::render {

Swapchain::Swapchain(const vk::Context& ctx, VkSurfaceKHR surface, uint32_t width, uint32_t height)
    : ctx_(ctx), surface_(ctx.instance(), surface) {
  if (!ctx.physical().getSurfaceSupportKHR(ctx.queue_family(), *surface_))
    throw Error("render", "window",
                fmt::format("{} cannot present to this window", ctx.caps().device_name),
                "choose another device (--device), or render headless with `masav run`");
  available_ = ::vk::raii::Semaphore(ctx.device(), ::vk::SemaphoreCreateInfo());
  finished_ = ::vk::raii::Semaphore(ctx.device(), ::vk::SemaphoreCreateInfo());
  build(width, height);
}

Swapchain::~Swapchain() {
  try {
    ctx_.device().waitIdle();
  } catch (...) {
  }
}

void Swapchain::build(uint32_t width, uint32_t height) {
  const auto caps = ctx_.physical().getSurfaceCapabilitiesKHR(*surface_);
  if (!(caps.supportedUsageFlags & ::vk::ImageUsageFlagBits::eTransferDst))
    throw Error("render", "window", "the window's images cannot be written by transfers",
                "render headless with `masav run`");
  const auto formats = ctx_.physical().getSurfaceFormatsKHR(*surface_);
  if (formats.empty())
    throw Error("render", "window", "the window offers no image formats", "report this driver");
  ::vk::SurfaceFormatKHR chosen = formats.front();
  for (const auto& f : formats)  // the frame is display-referred RGBA8: keep it as it is
    if (f.format == ::vk::Format::eB8G8R8A8Unorm || f.format == ::vk::Format::eR8G8B8A8Unorm) {
      chosen = f;
      break;
    }
  format_ = chosen.format;
  extent_ = caps.currentExtent.width != UINT32_MAX
                ? caps.currentExtent
                : ::vk::Extent2D{
                      std::clamp(width, caps.minImageExtent.width, caps.maxImageExtent.width),
                      std::clamp(height, caps.minImageExtent.height, caps.maxImageExtent.height)};
  uint32_t count = caps.minImageCount + 1;
  if (caps.maxImageCount) count = std::min(count, caps.maxImageCount);
  ::vk::SwapchainCreateInfoKHR info({}, *surface_, count, chosen.format, chosen.colorSpace, extent_,
                                    1, ::vk::ImageUsageFlagBits::eTransferDst,
                                    ::vk::SharingMode::eExclusive, {}, caps.currentTransform,
                                    ::vk::CompositeAlphaFlagBitsKHR::eOpaque,
                                    ::vk::PresentModeKHR::eFifo, true, *swapchain_);
  if (!(caps.supportedCompositeAlpha & ::vk::CompositeAlphaFlagBitsKHR::eOpaque))
    info.compositeAlpha = ::vk::CompositeAlphaFlagBitsKHR::eInherit;
  swapchain_ = ::vk::raii::SwapchainKHR(ctx_.device(), info);
  images_ = swapchain_.getImages();
}

void Swapchain::recreate(uint32_t width, uint32_t height) {
  ctx_.device().waitIdle();
  build(width, height);
}

bool Swapchain::acquire() {
  try {
    const auto [result, index] = swapchain_.acquireNextImage(UINT64_MAX, *available_);
    if (result == ::vk::Result::eErrorOutOfDateKHR) return false;
    index_ = index;
    return true;
  } catch (const ::vk::OutOfDateKHRError&) {
    return false;
  }
}

void Swapchain::record_blit(const ::vk::raii::CommandBuffer& cmd, ::vk::Image src, uint32_t src_w,
                            uint32_t src_h) const {
  using L = ::vk::ImageLayout;
  const ::vk::ImageSubresourceRange range(::vk::ImageAspectFlagBits::eColor, 0, 1, 0, 1);
  const ::vk::ImageMemoryBarrier to_dst({}, ::vk::AccessFlagBits::eTransferWrite, L::eUndefined,
                                        L::eTransferDstOptimal, VK_QUEUE_FAMILY_IGNORED,
                                        VK_QUEUE_FAMILY_IGNORED, images_[index_], range);
  cmd.pipelineBarrier(::vk::PipelineStageFlagBits::eTransfer,
                      ::vk::PipelineStageFlagBits::eTransfer, {}, {}, {}, to_dst);
  const ::vk::ImageSubresourceLayers layers(::vk::ImageAspectFlagBits::eColor, 0, 0, 1);
  const ::vk::ImageBlit blit(
      layers, {::vk::Offset3D{0, 0, 0}, ::vk::Offset3D{int32_t(src_w), int32_t(src_h), 1}}, layers,
      {::vk::Offset3D{0, 0, 0},
       ::vk::Offset3D{int32_t(extent_.width), int32_t(extent_.height), 1}});
  // Linear filtering only where the sizes differ: at the same size it would return each texel
  // anyway, and lavapipe blits nearest texels far faster.
  const bool same_size = src_w == extent_.width && src_h == extent_.height;
  cmd.blitImage(src, L::eTransferSrcOptimal, images_[index_], L::eTransferDstOptimal, blit,
                same_size ? ::vk::Filter::eNearest : ::vk::Filter::eLinear);
  const ::vk::ImageMemoryBarrier to_present(
      ::vk::AccessFlagBits::eTransferWrite, {}, L::eTransferDstOptimal, L::ePresentSrcKHR,
      VK_QUEUE_FAMILY_IGNORED, VK_QUEUE_FAMILY_IGNORED, images_[index_], range);
  cmd.pipelineBarrier(::vk::PipelineStageFlagBits::eTransfer,
                      ::vk::PipelineStageFlagBits::eBottomOfPipe, {}, {}, {}, to_present);
}

bool Swapchain::present() {
  const ::vk::SwapchainKHR sc = *swapchain_;
  const ::vk::Semaphore wait = *finished_;
  try {
    const auto r = ctx_.queue().presentKHR(::vk::PresentInfoKHR(wait, sc, index_));
    return r == ::vk::Result::eSuccess;
  } catch (const ::vk::OutOfDateKHRError&) {
    return false;
  }
}

}  // namespace masav::render
