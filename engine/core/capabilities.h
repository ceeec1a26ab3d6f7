#pragma once
// What a backend's device can do. Kernels check sizes against these limits before they allocate
// or dispatch, so a problem too large for the device fails with a message instead of a crash.
#include <cstdint>
#include <string>

namespace masav {

struct Capabilities {
  std::string backend;      // "vulkan", "cuda", "cpu"
  std::string device_name;  // e.g. "NVIDIA H100 80GB HBM3", "llvmpipe (LLVM 15.0.6, 256 bits)"
  std::string vendor;       // "NVIDIA", "AMD", "Intel", "Mesa", the CPU's vendor
  std::string device_type;  // "discrete", "integrated", "virtual", "cpu"
  std::string driver;       // driver name and version
  uint32_t subgroup_size = 1;       // the size kernels are specialised for
  uint32_t min_subgroup_size = 1;   // the smallest the device may use
  uint32_t max_workgroup_size = 1;
  uint32_t max_workgroups_x = 1;
  uint64_t shared_memory_bytes = 0;
  uint64_t max_buffer_bytes = 0;    // the largest single buffer a kernel can bind
  uint64_t device_memory_bytes = 0;
  double timestamp_period_ns = 1.0;
  bool real_is_double = false;      // Real/Real4 buffers hold fp64 (CPU reference) or fp32
  uint32_t threads = 1;             // CPU worker threads (1 for GPUs)
};

}  // namespace masav
