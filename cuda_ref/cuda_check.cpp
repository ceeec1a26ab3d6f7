#include "cuda_ref/cuda_check.h"

#include <fmt/format.h>

#include "engine/core/error.h"

namespace masav::cuda {
namespace {

std::string remedy_for(cudaError_t status) {
  if (status == cudaErrorMemoryAllocation) return "use fewer elements, or free other GPU work";
  if (status == cudaErrorNoKernelImageForDevice || status == cudaErrorUnsupportedPtxVersion)
    return "rebuild masav with this GPU's architecture in MASAV_CUDA_ARCHITECTURES";
  if (status == cudaErrorInsufficientDriver) return "update the NVIDIA driver";
  if (status == cudaErrorLaunchTimeout)
    return "a kernel ran past the display watchdog: use fewer elements or a GPU without a display";
  if (is_kernel_fault(status))
    return "a kernel read or wrote out of bounds or trapped: report it with the scene that "
           "triggers it";
  return "check the NVIDIA driver and the GPU's state (nvidia-smi)";
}

std::string describe(cudaError_t status) {
  return fmt::format("{} ({})", cudaGetErrorString(status), cudaGetErrorName(status));
}

}  // namespace

void check(cudaError_t status, const char* kernel, const char* what) {
  if (status == cudaSuccess) return;
  (void)cudaGetLastError();  // clear a non-sticky error so later calls can proceed
  throw Error("cuda", kernel, fmt::format("{} failed: {}", what, describe(status)),
              remedy_for(status));
}

bool is_kernel_fault(cudaError_t status) {
  switch (status) {
    case cudaErrorIllegalAddress:
    case cudaErrorLaunchTimeout:
    case cudaErrorAssert:
    case cudaErrorHardwareStackError:
    case cudaErrorIllegalInstruction:
    case cudaErrorMisalignedAddress:
    case cudaErrorInvalidAddressSpace:
    case cudaErrorInvalidPc:
    case cudaErrorLaunchFailure:
      return true;
    default:
      return false;
  }
}

void throw_kernel_fault(cudaError_t status, std::string_view where, std::string_view last_launch) {
  throw Error("cuda", std::string(last_launch),
              fmt::format("a kernel failed while it ran: {}; CUDA reported it at {}, and the last "
                          "kernel launched before that was {} (this one or an earlier one is the "
                          "culprit: kernels run asynchronously)",
                          describe(status), where, last_launch),
              "run with --tune cuda.sync_each_launch=on to name the faulting kernel exactly");
}

void throw_fault_of(cudaError_t status, std::string_view kernel) {
  throw Error("cuda", std::string(kernel),
              fmt::format("the kernel failed while it ran: {} (found by waiting for it, "
                          "cuda.sync_each_launch)",
                          describe(status)),
              remedy_for(status));
}

}  // namespace masav::cuda
