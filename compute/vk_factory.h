#pragma once
// Entry points the registry uses (kept free of Vulkan headers).
#include <memory>
#include <string_view>

#include "engine/core/backend_status.h"
#include "engine/kernels/backend_factory.h"

namespace masav::vk {

BackendStatus backend_status();
// The request's context options, else the environment's (compute/device/vk_environment.h);
// `device` overrides the device; the request's tuning and loop counting are the backend's.
std::unique_ptr<Backend> create_backend(std::string_view device, const BackendRequest& request);

}  // namespace masav::vk
