#pragma once
// Every CUDA call and launch is checked; a failure becomes masav::Error naming the kernel.
#include <cuda_runtime_api.h>

#include <string_view>

namespace masav::cuda {

void check(cudaError_t status, const char* kernel, const char* what);

// The errors a kernel raises while it runs (illegal address, device assert, trap, ...). CUDA
// reports them at some later call on any stream, so that call's name is not the culprit's.
bool is_kernel_fault(cudaError_t status);

// A kernel fault that surfaced at `where`: names `last_launch`, the last kernel launched before
// that point, which is the culprit or ran after it.
[[noreturn]] void throw_kernel_fault(cudaError_t status, std::string_view where,
                                     std::string_view last_launch);

// A kernel fault found by waiting right after `kernel`'s launch (--tune cuda.sync_each_launch=on): it is the
// culprit.
[[noreturn]] void throw_fault_of(cudaError_t status, std::string_view kernel);

}  // namespace masav::cuda
