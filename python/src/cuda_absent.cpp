// A build without the CUDA backend: no buffer is a CUDA buffer.
#include "python/src/cuda_memory.h"

namespace masav::python {

void* cuda_pointer(BufferImpl&) {
  return nullptr;
}

int cuda_device_of(void*) {
  return -1;
}

}  // namespace masav::python
