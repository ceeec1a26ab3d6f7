#pragma once
// Entry points the registry uses (kept free of Vulkan headers).
#include <memory>
#include <string_view>

#include "engine/core/backend_status.h"
#include "engine/kernels/backend_factory.h"

namespace masav::vk {

BackendStatus backend_status();
// Options from the environment (MASAV_VK_DEVICE, MASAV_VK_VALIDATION) or the request's;
// `device` overrides the device; the request may ask for loop counting.
std::unique_ptr<Backend> create_backend(std::string_view device, const BackendRequest& request);

}  // namespace masav::vk
