#pragma once
// A CUDA buffer's device pointer, for __cuda_array_interface__ and DLPack (cuda_pointer.cpp in a
// build with the CUDA backend, cuda_absent.cpp otherwise, chosen by python/CMakeLists.txt).
#include "engine/core/buffer.h"

namespace masav::python {

// The buffer's device pointer if it is a CUDA buffer; null otherwise.
void* cuda_pointer(BufferImpl& b);
// The CUDA device that holds `ptr` (a pointer cuda_pointer returned).
int cuda_device_of(void* ptr);

}  // namespace masav::python
