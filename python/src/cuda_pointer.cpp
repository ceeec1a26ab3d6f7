// A build with the CUDA backend: its buffers' device pointers and the device that holds them.
#include <cuda_runtime_api.h>

#include "cuda_ref/cuda_backend.h"
#include "python/src/cuda_memory.h"

namespace masav::python {

void* cuda_pointer(BufferImpl& b) {
  auto* c = dynamic_cast<cuda::CudaBuffer*>(&b);
  return c ? c->ptr() : nullptr;
}

int cuda_device_of(void* ptr) {
  cudaPointerAttributes a{};
  if (cudaPointerGetAttributes(&a, ptr) != cudaSuccess) {
    cudaGetLastError();  // clear the sticky-free error so later calls see their own
    return 0;
  }
  return a.device;
}

}  // namespace masav::python
