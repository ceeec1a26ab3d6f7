#include "compute/vk_factory.h"

#include "compute/vk_backend.h"
#include "engine/core/error.h"

namespace masav::vk {

BackendStatus backend_status(const BackendRequest& request) {
  BackendStatus s;
  s.name = "vulkan";
  s.built = true;
  try {
    for (const auto& d :
         Context::list_devices(request.vulkan ? *request.vulkan : ContextOptions{})) {
      DeviceStatus ds;
      ds.index = d.index;
      ds.name = d.name;
      ds.type = d.type;
      ds.detail = "Vulkan " + d.api_version;
      ds.usable = d.usable;
      ds.reason = d.reason;
      s.available = s.available || d.usable;
      s.devices.push_back(ds);
    }
    if (s.devices.empty())
      s.reason = "no Vulkan device (install mesa-vulkan-drivers for lavapipe, or a GPU driver)";
    else if (!s.available)
      s.reason = "no device meets masav's needs (Vulkan 1.1, subgroup arithmetic and shuffle)";
  } catch (const Error& e) {
    s.reason = e.what();
  } catch (const std::exception& e) {
    s.reason = std::string("Vulkan error: ") + e.what();
  }
  return s;
}

std::unique_ptr<Backend> create_backend(std::string_view device, const BackendRequest& request) {
  BackendOptions o;
  o.context = request.vulkan ? *request.vulkan : ContextOptions{};
  if (!device.empty()) o.context.device_selector = std::string(device);
  o.context.max_buffer_bytes = request.tuning.vulkan.max_buffer_mib << 20;
  o.context.max_texels = request.tuning.vulkan.max_texels;
  o.tuning = request.tuning;
  o.count_loop_ticks = request.count_loop_ticks;
  o.cache_dir = request.cache_dir;
  try {
    return std::make_unique<VulkanBackend>(o);
  } catch (const Error&) {
    throw;
  } catch (const ::vk::SystemError& e) {
    throw Error("vulkan", "", std::string("device set-up failed: ") + e.what(),
                "update the Vulkan driver or choose another device (masav info)");
  }
}

}  // namespace masav::vk
