#pragma once
// Lists the backends built into this binary and their devices, and creates one by name.
// `auto` picks CUDA if it has a device, else Vulkan, else the CPU reference.
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "engine/core/backend.h"
#include "engine/core/backend_status.h"

namespace masav {

std::vector<BackendStatus> list_backends();
// The backend `auto` resolves to right now.
std::string auto_backend_name();
// name: vulkan | cuda | cpu | auto. device: index or part of a name ("" = the best one).
// Throws masav::Error naming the backend and what to install when it cannot be created.
std::unique_ptr<Backend> create_backend(std::string_view name, std::string_view device = "");
const std::vector<std::string>& backend_names();  // vulkan, cuda, cpu

}  // namespace masav
