#include "render/render_device.h"

#include <fmt/format.h>

#include "engine/core/error.h"
#include "registry/backends.h"

namespace masav::render {

vk::ContextOptions graphics_options(const std::string& device) {
  vk::ContextOptions o = vk::options_from_env();
  if (!device.empty()) o.device_selector = device;
  o.graphics = true;
  return o;
}

std::unique_ptr<Backend> open_compute_backend(const std::string& name, const std::string& device,
                                              const vk::ContextOptions& options) {
  return create_backend(name, device, BackendRequest{.vulkan = &options});
}

RenderDevice::RenderDevice(Backend& compute, const vk::ContextOptions& options)
    : compute_(compute) {
  const VulkanInterop* vi = compute.vulkan_interop();
  if (vi && vi->vulkan_context().graphics()) {
    shared_ = vi;
    ctx_ = &vi->vulkan_context();
  } else {
    try {
      owned_ = std::make_unique<vk::Context>(options);
    } catch (const Error& e) {
      throw Error("render", "",
                  fmt::format("masav draws with Vulkan, which is not usable here: {}", e.problem()),
                  e.remedy().empty() ? "install libvulkan1 and mesa-vulkan-drivers" : e.remedy());
    }
    ctx_ = owned_.get();
  }
  pool_ = ::vk::raii::CommandPool(
      device(), ::vk::CommandPoolCreateInfo(::vk::CommandPoolCreateFlagBits::eResetCommandBuffer,
                                            ctx_->queue_family()));
  ::vk::raii::CommandBuffers bufs(
      device(), ::vk::CommandBufferAllocateInfo(*pool_, ::vk::CommandBufferLevel::ePrimary, 1));
  cmd_ = std::move(bufs.front());
  fence_ = ::vk::raii::Fence(device(), ::vk::FenceCreateInfo());
}

RenderDevice::~RenderDevice() {
  try {
    device().waitIdle();
  } catch (...) {
  }
}

const ::vk::raii::CommandBuffer& RenderDevice::begin() {
  if (!recording_) {
    cmd_.reset();
    cmd_.begin(::vk::CommandBufferBeginInfo(::vk::CommandBufferUsageFlagBits::eOneTimeSubmit));
    recording_ = true;
  }
  return cmd_;
}

void RenderDevice::submit(::vk::Semaphore wait, ::vk::PipelineStageFlags wait_stage,
                          ::vk::Semaphore signal) {
  if (!recording_) return;
  cmd_.end();
  recording_ = false;
  ::vk::CommandBuffer raw = *cmd_;
  ::vk::SubmitInfo info;
  info.setCommandBuffers(raw);
  if (wait) info.setWaitSemaphores(wait).setWaitDstStageMask(wait_stage);
  if (signal) info.setSignalSemaphores(signal);
  try {
    ctx_->queue().submit(info, *fence_);
    while (device().waitForFences(*fence_, VK_TRUE, UINT64_MAX) == ::vk::Result::eTimeout) {
    }
  } catch (const ::vk::DeviceLostError&) {
    throw Error("render", "submit", fmt::format("device lost on {}", ctx_->caps().device_name),
                "the GPU reset or a draw faulted; restart masav, and report the scene");
  }
  device().resetFences(*fence_);
}

ImageMemory make_image(const vk::Context& ctx, const ::vk::ImageCreateInfo& info,
                       ::vk::ImageAspectFlags aspect, const std::string& label) {
  ImageMemory m;
  try {
    m.image = ::vk::raii::Image(ctx.device(), info);
    const auto req = m.image.getMemoryRequirements();
    const auto mem = ctx.physical().getMemoryProperties();
    std::optional<uint32_t> type;
    for (uint32_t i = 0; i < mem.memoryTypeCount && !type; ++i)
      if ((req.memoryTypeBits & (1u << i)) &&
          (mem.memoryTypes[i].propertyFlags & ::vk::MemoryPropertyFlagBits::eDeviceLocal))
        type = i;
    for (uint32_t i = 0; i < mem.memoryTypeCount && !type; ++i)
      if (req.memoryTypeBits & (1u << i)) type = i;
    if (!type) throw Error("render", label, "no memory type for the image", "report this device");
    m.memory = ::vk::raii::DeviceMemory(ctx.device(), ::vk::MemoryAllocateInfo(req.size, *type));
    m.image.bindMemory(*m.memory, 0);
    m.view = ::vk::raii::ImageView(
        ctx.device(), ::vk::ImageViewCreateInfo({}, *m.image, ::vk::ImageViewType::e2D, info.format,
                                                {}, {aspect, 0, 1, 0, 1}));
  } catch (const ::vk::OutOfDeviceMemoryError&) {
    throw Error("render", label,
                fmt::format("out of device memory for a {}x{} image", info.extent.width,
                            info.extent.height),
                "render smaller frames (render.width, render.height)");
  }
  return m;
}

}  // namespace masav::render
