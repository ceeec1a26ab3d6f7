#pragma once
// Every CUDA call and launch is checked; a failure becomes masav::Error naming the kernel.
#include <cuda_runtime_api.h>

#include <string>

namespace masav::cuda {

void check(cudaError_t status, const char* kernel, const char* what);
// After a launch: the launch error (bad configuration, no kernel image for this GPU).
inline void check_launch(const char* kernel) { check(cudaGetLastError(), kernel, "launch"); }

}  // namespace masav::cuda
