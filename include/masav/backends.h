#pragma once
/// \file
/// Backends: the kernel set on one device. `masav::Backend` (engine/kernels/backend.h) has one
/// method per kernel of the kernel list (kernels.h) and typed buffers (`create<T>`, `upload`,
/// `download`); every backend built into the library is available by name at run time, and one
/// that was not built or has no device is reported, never a link error.
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "engine/core/backend_status.h"
#include "engine/core/tuning.h"
#include "engine/kernels/backend.h"

namespace masav {

/// How to open a backend.
struct BackendOptions {
  /// `cpu` (the double-precision reference), `vulkan`, `cuda`, or `auto`: CUDA if it has a
  /// device, else Vulkan, else the CPU reference.
  std::string name = "auto";
  /// A device index or part of its name; empty: the best one.
  std::string device;
  /// The code-path choices and limits (docs/backends.md); every option defaults to automatic.
  Tuning tuning;
  /// The directory of the Vulkan pipeline cache; empty: no cache, every run compiles its
  /// pipelines again. The library never reads the environment: the `masav` command line's
  /// MASAV_CACHE_DIR (docs/backends.md) is this option.
  std::string cache_dir;
  /// Vulkan: the Khronos validation layer, every message printed to stderr (the command line's
  /// MASAV_VK_VALIDATION=1). Needs the validation layers installed.
  bool vulkan_validation = false;
  /// Vulkan: the loader library to open, a path or a name the dynamic linker searches (the
  /// command line's MASAV_VULKAN_LOADER).
  std::string vulkan_loader = "libvulkan.so.1";
};

/// Opens a backend. Throws masav::Error naming the backend and what to install when it cannot
/// be created.
std::unique_ptr<Backend> open_backend(const BackendOptions& options = {});

/// Opens the backend `name` (cpu, vulkan, cuda or auto) on its best device.
std::unique_ptr<Backend> open_backend(std::string_view name);

/// Every backend masav knows: whether it was built, whether it is available, why not, and its
/// devices (what `masav info` prints). Vulkan's devices as the default loader lists them.
std::vector<BackendStatus> backend_report();

/// The same, with Vulkan's devices listed through `options.vulkan_loader` (the other fields
/// are not read).
std::vector<BackendStatus> backend_report(const BackendOptions& options);

/// The names of the backends that can be opened on this machine now, best first.
std::vector<std::string> usable_backends();

/// Tuning options from `key=value` assignments separated by spaces, as `--tune` takes them
/// (e.g. `"cpu.threads=2 vulkan.replay=off"`). Throws masav::Error naming a key or value that
/// does not exist.
Tuning parse_tuning(std::string_view assignments);

}  // namespace masav
