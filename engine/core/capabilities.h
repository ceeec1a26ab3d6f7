#pragma once
// What a backend's device can do. Kernels check sizes against these limits before they allocate
// or dispatch, so a problem too large for the device fails with a message instead of a crash.
#include <cstdint>
#include <string>

namespace masav {

// The loop budget of one shader invocation masav's kernels are sized for: lavapipe stops an
// invocation after 65,535 loop iterations, silently (PLATFORM.md), the strictest device masav
// supports. Scene settings are checked against it before a device is chosen.
inline constexpr uint32_t kPortableLoopBudget = 65535;

struct Capabilities {
  std::string backend;         // "vulkan", "cuda", "cpu"
  std::string device_name;     // e.g. "NVIDIA H100 80GB HBM3", "llvmpipe (LLVM 15.0.6, 256 bits)"
  std::string vendor;          // "NVIDIA", "AMD", "Intel", "Mesa", the CPU's vendor
  std::string device_type;     // "discrete", "integrated", "virtual", "cpu"
  std::string driver;          // driver name and version
  uint32_t subgroup_size = 1;  // the size kernels are specialised for
  uint32_t min_subgroup_size = 1;  // the smallest the device may use
  uint32_t max_workgroup_size = 1;
  uint32_t max_workgroups_x = 1;
  uint64_t shared_memory_bytes = 0;
  uint64_t max_buffer_bytes = 0;  // the largest single buffer a kernel can bind
  uint64_t device_memory_bytes = 0;
  double timestamp_period_ns = 1.0;
  bool real_is_double = false;  // Real/Real4 buffers hold fp64 (CPU reference) or fp32
  // The SPH density and force pair terms are summed in fp32 even though Real is fp64 (the CPU
  // backend with CpuTuning::sph_precision = fp32).
  bool sph_pairs_fp32 = false;
  uint32_t threads = 1;         // CPU worker threads (1 for GPUs)
  // The most loop iterations one shader invocation may run: lavapipe's own limit. A device
  // without one reports the portable budget, so that every backend accepts the same parameters
  // and the cross-check can compare any two of them. Kernels bound their loops by it (candidate
  // caps, ray samples, path steps) and the tests drive each kernel's worst case against it.
  uint32_t max_loop_iterations = kPortableLoopBudget;
};

}  // namespace masav
