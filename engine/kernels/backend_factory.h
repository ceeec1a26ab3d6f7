#pragma once
// What constructs backends by name. The registry (registry/backends.h) is the one factory built
// into masav; the code below it that needs a second backend (the cross-check's reference)
// receives a factory instead of linking the backends itself.
#include <filesystem>
#include <memory>
#include <string_view>
#include <vector>

#include "engine/core/backend_status.h"
#include "engine/core/tuning.h"
#include "engine/kernels/backend.h"

namespace masav {

namespace vk {
struct ContextOptions;  // compute/device/vk_context.h
}

// What a caller needs of a backend beyond its kernels. Everything comes from the caller: the
// library never reads the process environment (the masav command line resolves its variables,
// docs/backends.md).
struct BackendRequest {
  // A Vulkan backend's settings: device, validation, the loader library, a graphics queue and
  // the window's extensions for the renderer that borrows its device (null: ContextOptions'
  // defaults; other backends ignore it).
  const vk::ContextOptions* vulkan = nullptr;
  // The directory of the Vulkan pipeline cache (engine/util/cache_dir.h); empty = no cache:
  // every run compiles its pipelines again.
  std::filesystem::path cache_dir;
  bool count_loop_ticks = false;  // instrument every loop: Backend::take_max_loop_ticks
  Tuning tuning;                  // every option automatic unless set (engine/core/tuning.h)
};

class BackendFactory {
 public:
  virtual ~BackendFactory() = default;
  // Every backend built into this binary, with its devices or why it is unavailable; Vulkan's
  // as request.vulkan opens it (its loader library).
  virtual std::vector<BackendStatus> list(const BackendRequest& request = {}) const = 0;
  // name: vulkan | cuda | cpu | auto; device: index or part of a name ("" = the best one).
  // Throws masav::Error naming the backend and what to install when it cannot be created.
  virtual std::unique_ptr<Backend> create(std::string_view name, std::string_view device = "",
                                          const BackendRequest& request = {}) const = 0;
};

}  // namespace masav
