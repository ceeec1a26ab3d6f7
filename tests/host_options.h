#pragma once
// The render tests' Vulkan and cache settings from the environment, as the masav command line
// reads it (app/host_environment.h): ctest sets MASAV_VK_VALIDATION=1 and MASAV_CACHE_DIR for
// them, and the libraries take both as options, never from the environment.
#include <string>

#include "app/host_environment.h"
#include "render/render_device.h"

namespace masav::test {

// A rendering context's options: the environment's device, validation and loader.
inline vk::ContextOptions graphics_options() {
  return render::graphics_options(app::vulkan_options(app::host_environment()));
}

// The caches' directory the environment names ("" = none).
inline std::string cache_dir() {
  return app::host_environment().cache_dir().string();
}

}  // namespace masav::test
