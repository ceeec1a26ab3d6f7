#pragma once
// Entry points the registry uses (kept free of Vulkan headers).
#include <memory>
#include <string_view>

#include "engine/core/backend.h"
#include "engine/core/backend_status.h"

namespace masav::vk {

BackendStatus backend_status();
// Options from the environment (MASAV_VK_DEVICE, MASAV_VK_VALIDATION); `device` overrides.
std::unique_ptr<Backend> create_backend(std::string_view device);

}  // namespace masav::vk
