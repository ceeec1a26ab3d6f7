#pragma once
// The backends built into this binary, their devices, and construction by name: the one
// BackendFactory of masav, above the engine (which only receives it). `auto` picks CUDA if it
// has a device, else Vulkan, else the CPU reference.
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "engine/core/backend_status.h"
#include "engine/kernels/backend_factory.h"

namespace masav {

const BackendFactory& backend_factory();

// The same, as free functions. Vulkan is listed and probed as request.vulkan would open it (its
// loader library; null: the defaults).
std::vector<BackendStatus> list_backends(const BackendRequest& request = {});
// The backend `auto` resolves to right now.
std::string auto_backend_name(const BackendRequest& request = {});
// name: vulkan | cuda | cpu | auto. device: index or part of a name ("" = the best one).
// Throws masav::Error naming the backend and what to install when it cannot be created.
std::unique_ptr<Backend> create_backend(std::string_view name, std::string_view device = "",
                                        const BackendRequest& request = {});
const std::vector<std::string>& backend_names();  // vulkan, cuda, cpu

// The Vulkan settings of a caller built without the Vulkan headers (the public API, the Python
// module): the part of vk::ContextOptions it chooses, every other field at its default.
struct VulkanSettings {
  bool validation = false;                // the Khronos validation layer with a debug messenger
  std::string loader = "libvulkan.so.1";  // the loader library dlopen opens
};
// create_backend and list_backends with request.vulkan made from `vulkan`.
std::unique_ptr<Backend> create_backend(std::string_view name, std::string_view device,
                                        const BackendRequest& request,
                                        const VulkanSettings& vulkan);
std::vector<BackendStatus> list_backends(const VulkanSettings& vulkan);

}  // namespace masav
