#pragma once
// Entry points the registry uses; plain C++ (no CUDA headers), so any TU can include it.
#include <memory>
#include <string_view>

#include "engine/core/backend_status.h"
#include "engine/kernels/backend.h"

namespace masav::cuda {

// Unavailable, with the reason, when there is no driver or no device.
BackendStatus backend_status();
// device: index or part of the name ("" = device 0); tuning: its `cuda` part is this backend's.
std::unique_ptr<Backend> create_backend(std::string_view device, const Tuning& tuning = {});

}  // namespace masav::cuda
