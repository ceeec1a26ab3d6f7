#pragma once
// Every environment variable masav honours, read once at startup: only programs (the masav
// command line, the test mains) read the environment; the libraries take these values as typed
// options (docs/backends.md). The loader's own VK_DRIVER_FILES and VK_ICD_FILENAMES are read
// only to name a wrong manifest when Vulkan fails to start.
#include <filesystem>
#include <string>

#include "engine/kernels/backend_factory.h"
#include "engine/util/cache_dir.h"

#if MASAV_HAVE_VULKAN
#include "compute/device/vk_context.h"
#endif

namespace masav::app {

// The variables' values; "" = unset (or set to "").
struct HostEnvironment {
  CacheDirInputs cache;          // MASAV_CACHE_DIR, XDG_CACHE_HOME, HOME
  std::string vk_device;         // MASAV_VK_DEVICE: an index or part of a name
  std::string vk_validation;     // MASAV_VK_VALIDATION: 1/on/true or 0/off/false
  std::string vulkan_loader;     // MASAV_VULKAN_LOADER: the loader library
  std::string vk_driver_files;   // VK_DRIVER_FILES
  std::string vk_icd_filenames;  // VK_ICD_FILENAMES

  // The caches' directory (engine/util/cache_dir.h); empty: none, each run recomputes.
  std::filesystem::path cache_dir() const;
  // MASAV_VK_VALIDATION as a switch; throws masav::Error naming the variable on another value.
  bool validation() const;
};

HostEnvironment read_host_environment();

// The snapshot the masav command line took at startup (read once, on first use).
const HostEnvironment& host_environment();

#if MASAV_HAVE_VULKAN
// The Vulkan settings the variables choose (device, validation, loader, the manifests' names),
// every other field at its default. Throws as HostEnvironment::validation does.
vk::ContextOptions vulkan_options(const HostEnvironment& env);
#endif

// The snapshot as a BackendRequest: its cache directory and Vulkan options (held here, where the
// request points: the object outlives every use of get()), with `tuning`.
class HostRequest {
 public:
  explicit HostRequest(const HostEnvironment& env, const Tuning& tuning = {});
  HostRequest(const HostRequest&) = delete;
  HostRequest& operator=(const HostRequest&) = delete;
  const BackendRequest& get() const { return request_; }

 private:
#if MASAV_HAVE_VULKAN
  vk::ContextOptions vulkan_;
#endif
  BackendRequest request_;
};

}  // namespace masav::app
