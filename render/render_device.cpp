#include "render/render_device.h"

#include <fmt/format.h>

#include "engine/core/error.h"
#include "registry/backends.h"

namespace masav::render {

vk::ContextOptions graphics_options(vk::ContextOptions base, const std::string& device) {
  if (!device.empty()) base.device_selector = device;
  base.graphics = true;
  return base;
}

std::unique_ptr<Backend> open_compute_backend(const std::string& name, const std::string& device,
                                              const vk::ContextOptions& options,
                                              const Tuning& tuning,
                                              const std::filesystem::path& cache_dir) {
  return create_backend(
      name, device, BackendRequest{.vulkan = &options, .cache_dir = cache_dir, .tuning = tuning});
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
  cmds_ = std::make_unique<vk::Commands>(*ctx_);
}

RenderDevice::~RenderDevice() {
  try {
    device().waitIdle();
  } catch (...) {
  }
}

const ::vk::raii::CommandBuffer& RenderDevice::begin() {
  return cmds_->begin();
}

void RenderDevice::submit(::vk::Semaphore wait, ::vk::PipelineStageFlags wait_stage,
                          ::vk::Semaphore signal) {
  cmds_->submit_and_wait("render",
                         "the GPU reset or a draw faulted; restart masav, and report the scene",
                         wait, wait_stage, signal);
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
