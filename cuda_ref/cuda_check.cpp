#include "cuda_ref/cuda_check.h"

#include <fmt/format.h>

#include "engine/core/error.h"

namespace masav::cuda {

void check(cudaError_t status, const char* kernel, const char* what) {
  if (status == cudaSuccess) return;
  std::string remedy = "check the NVIDIA driver and the GPU's state (nvidia-smi)";
  if (status == cudaErrorMemoryAllocation) remedy = "use fewer elements, or free other GPU work";
  if (status == cudaErrorNoKernelImageForDevice || status == cudaErrorUnsupportedPtxVersion)
    remedy = "rebuild masav with this GPU's architecture in MASAV_CUDA_ARCHITECTURES";
  if (status == cudaErrorInsufficientDriver) remedy = "update the NVIDIA driver";
  (void)cudaGetLastError();  // clear a non-sticky error so later calls can proceed
  throw Error("cuda", kernel, fmt::format("{} failed: {} ({})", what, cudaGetErrorString(status),
                                          cudaGetErrorName(status)), remedy);
}

}  // namespace masav::cuda
