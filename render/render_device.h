#pragma once
// The Vulkan device the renderer draws with. When the compute backend is Vulkan (opened with
// graphics, see open_compute_backend) the renderer borrows that backend's device, so kernel
// outputs are drawn where they lie; otherwise (CUDA, the CPU reference) it opens a device of its
// own and the kernel outputs are copied over (layer_bridge.h).
#include <filesystem>
#include <functional>
#include <memory>
#include <string>

#include "compute/device/vk_commands.h"
#include "compute/device/vk_context.h"
#include "engine/kernels/backend.h"

namespace masav::render {

// Options for a rendering context: the caller's `base` (device, validation, loader: the masav
// command line's from its environment), `device` instead of its device when given, and a
// graphics queue required.
vk::ContextOptions graphics_options(vk::ContextOptions base = {}, const std::string& device = "");

// The compute backend for a scene that is drawn, from the registry: a Vulkan one (also "auto"
// when it resolves to Vulkan) on a device that can also draw, with `options`; `tuning` as the
// caller was given it (--tune); the pipeline cache in cache_dir (empty: none).
std::unique_ptr<Backend> open_compute_backend(const std::string& name, const std::string& device,
                                              const vk::ContextOptions& options,
                                              const Tuning& tuning = {},
                                              const std::filesystem::path& cache_dir = {});

class RenderDevice {
 public:
  // Borrows `compute`'s device when it is a Vulkan backend opened with graphics; else opens one
  // with `options`.
  RenderDevice(Backend& compute, const vk::ContextOptions& options);
  ~RenderDevice();

  const vk::Context& ctx() const { return *ctx_; }
  const ::vk::raii::Device& device() const { return ctx_->device(); }
  // The compute backend's Vulkan device and buffers when the renderer draws from them directly,
  // or null when it copies.
  const VulkanInterop* shared() const { return shared_; }
  Backend& compute() const { return compute_; }

  // One command buffer, recorded and submitted per frame; submit() waits for it.
  const ::vk::raii::CommandBuffer& begin();
  void submit(::vk::Semaphore wait = {}, ::vk::PipelineStageFlags wait_stage = {},
              ::vk::Semaphore signal = {});

 private:
  Backend& compute_;
  const VulkanInterop* shared_ = nullptr;
  std::unique_ptr<vk::Context> owned_;
  const vk::Context* ctx_ = nullptr;
  std::unique_ptr<vk::Commands> cmds_;
};

// Device memory for an image (the render targets), device-local.
struct ImageMemory {
  ::vk::raii::Image image = nullptr;
  ::vk::raii::DeviceMemory memory = nullptr;
  ::vk::raii::ImageView view = nullptr;
};
ImageMemory make_image(const vk::Context& ctx, const ::vk::ImageCreateInfo& info,
                       ::vk::ImageAspectFlags aspect, const std::string& label);

}  // namespace masav::render
