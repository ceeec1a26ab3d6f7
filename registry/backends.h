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

// The same, as free functions.
std::vector<BackendStatus> list_backends();
// The backend `auto` resolves to right now.
std::string auto_backend_name();
// name: vulkan | cuda | cpu | auto. device: index or part of a name ("" = the best one).
// Throws masav::Error naming the backend and what to install when it cannot be created.
std::unique_ptr<Backend> create_backend(std::string_view name, std::string_view device = "",
                                        const BackendRequest& request = {});
const std::vector<std::string>& backend_names();  // vulkan, cuda, cpu

}  // namespace masav
