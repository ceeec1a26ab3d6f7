#include "render/offscreen_target.h"

#include <fmt/format.h>

#include <cstring>

#include "engine/core/error.h"

namespace masav::render {
namespace {

constexpr ::vk::Format kDepthFormat = ::vk::Format::eD32Sfloat;

}  // namespace

::vk::raii::RenderPass make_render_pass(const vk::Context& ctx, bool continued) {
  using L = ::vk::ImageLayout;
  using Op = ::vk::AttachmentLoadOp;
  const Op load = continued ? Op::eLoad : Op::eClear;
  // Depth is kept between the passes of one frame (the fluid surface's passes).
  const ::vk::AttachmentDescription attachments[2] = {
      {{},
       kColorFormat,
       ::vk::SampleCountFlagBits::e1,
       load,
       ::vk::AttachmentStoreOp::eStore,
       Op::eDontCare,
       ::vk::AttachmentStoreOp::eDontCare,
       continued ? L::eTransferSrcOptimal : L::eUndefined,
       L::eTransferSrcOptimal},
      {{},
       kDepthFormat,
       ::vk::SampleCountFlagBits::e1,
       load,
       ::vk::AttachmentStoreOp::eStore,
       Op::eDontCare,
       ::vk::AttachmentStoreOp::eDontCare,
       continued ? L::eDepthStencilAttachmentOptimal : L::eUndefined,
       L::eDepthStencilAttachmentOptimal}};
  const ::vk::AttachmentReference color_ref(0, L::eColorAttachmentOptimal);
  const ::vk::AttachmentReference depth_ref(1, L::eDepthStencilAttachmentOptimal);
  ::vk::SubpassDescription subpass({}, ::vk::PipelineBindPoint::eGraphics, {}, color_ref, {},
                                   &depth_ref);
  using S = ::vk::PipelineStageFlagBits;
  using A = ::vk::AccessFlagBits;
  // In: the previous frame's transfer (readback, blit) of the same image is done before we
  // clear it, and a continued pass waits for the frame's earlier passes (attachments, and the
  // storage buffers their fragment shaders wrote). Out: colour writes are visible to the
  // readback copy and the blit. Both passes have the same dependencies: pipelines and the
  // framebuffer are made against one of them, and compatible passes differ only in load
  // operations and layouts.
  const ::vk::PipelineStageFlags earlier = S::eTransfer | S::eColorAttachmentOutput |
                                           S::eEarlyFragmentTests | S::eLateFragmentTests |
                                           S::eFragmentShader;
  const ::vk::PipelineStageFlags later =
      S::eColorAttachmentOutput | S::eEarlyFragmentTests | S::eFragmentShader;
  const ::vk::SubpassDependency deps[2] = {
      {VK_SUBPASS_EXTERNAL, 0, earlier, later,
       A::eTransferRead | A::eColorAttachmentWrite | A::eDepthStencilAttachmentWrite |
           A::eShaderWrite,
       A::eColorAttachmentRead | A::eColorAttachmentWrite | A::eDepthStencilAttachmentRead |
           A::eDepthStencilAttachmentWrite | A::eShaderRead | A::eShaderWrite},
      {0, VK_SUBPASS_EXTERNAL, S::eColorAttachmentOutput, S::eTransfer, A::eColorAttachmentWrite,
       A::eTransferRead}};
  return ::vk::raii::RenderPass(ctx.device(),
                                ::vk::RenderPassCreateInfo({}, attachments, subpass, deps));
}

OffscreenTarget::OffscreenTarget(const vk::Context& ctx, ::vk::RenderPass pass, uint32_t width,
                                 uint32_t height)
    : ctx_(ctx), width_(width), height_(height) {
  const auto limits = ctx.physical().getProperties().limits;
  if (width > limits.maxFramebufferWidth || height > limits.maxFramebufferHeight)
    throw Error("render", "target",
                fmt::format("{}x{} exceeds this device's largest frame {}x{}", width, height,
                            limits.maxFramebufferWidth, limits.maxFramebufferHeight),
                fmt::format("use render.width <= {} and render.height <= {}",
                            limits.maxFramebufferWidth, limits.maxFramebufferHeight));
  using U = ::vk::ImageUsageFlagBits;
  ::vk::ImageCreateInfo info({}, ::vk::ImageType::e2D, kColorFormat, {width, height, 1}, 1, 1,
                             ::vk::SampleCountFlagBits::e1, ::vk::ImageTiling::eOptimal,
                             U::eColorAttachment | U::eTransferSrc);
  color_ = make_image(ctx, info, ::vk::ImageAspectFlagBits::eColor, "colour target");
  info.format = kDepthFormat;
  info.usage = U::eDepthStencilAttachment;
  depth_ = make_image(ctx, info, ::vk::ImageAspectFlagBits::eDepth, "depth target");
  const ::vk::ImageView views[2] = {*color_.view, *depth_.view};
  framebuffer_ = ::vk::raii::Framebuffer(
      ctx.device(), ::vk::FramebufferCreateInfo({}, pass, views, width, height, 1));
  readback_ = vk::allocate(ctx, ::vk::DeviceSize(width) * height * 4, vk::MemoryUse::readback,
                           "frame readback");
}

void OffscreenTarget::record_readback(const ::vk::raii::CommandBuffer& cmd) {
  const ::vk::BufferImageCopy region(0, 0, 0, {::vk::ImageAspectFlagBits::eColor, 0, 0, 1},
                                     {0, 0, 0}, {width_, height_, 1});
  cmd.copyImageToBuffer(*color_.image, ::vk::ImageLayout::eTransferSrcOptimal, *readback_->buffer,
                        region);
  const ::vk::MemoryBarrier to_host(::vk::AccessFlagBits::eTransferWrite,
                                    ::vk::AccessFlagBits::eHostRead);
  cmd.pipelineBarrier(::vk::PipelineStageFlagBits::eTransfer, ::vk::PipelineStageFlagBits::eHost,
                      {}, to_host, {}, {});
}

std::vector<uint8_t> OffscreenTarget::pixels() const {
  vk::invalidate_for_host(ctx_, *readback_);
  std::vector<uint8_t> out(size_t(width_) * height_ * 4);
  std::memcpy(out.data(), readback_->mapped, out.size());
  return out;
}

}  // namespace masav::render
