#pragma once
// Entry points the registry uses (kept free of Vulkan headers).
#include <memory>
#include <string_view>

#include "engine/core/backend_status.h"
#include "engine/kernels/backend_factory.h"

namespace masav::vk {

// The devices as request.vulkan (null: the default ContextOptions) opens the loader.
BackendStatus backend_status(const BackendRequest& request);
// The request's context options, else the defaults (never the environment: the library takes
// its options from the caller); `device` overrides the device; the request's tuning, loop
// counting and pipeline cache directory are the backend's.
std::unique_ptr<Backend> create_backend(std::string_view device, const BackendRequest& request);

}  // namespace masav::vk
