#pragma once
// The DLPack exchange structs (the ABI of dlpack.h v0.8, the "dltensor" capsule numpy, CuPy and
// PyTorch take), written from the published specification: a consumer reads these fields by
// position, so their order and types are the ABI. And the capsule masav.Buffer.__dlpack__ makes.
#include <cstdint>

#include "python/src/py_core.h"

namespace masav::python {

// DLDeviceType: where the data pointer points.
enum DLDeviceType : int32_t {
  kDLCPU = 1,
  kDLCUDA = 2,
  kDLVulkan = 7,
};

struct DLDevice {
  DLDeviceType device_type;
  int32_t device_id;
};

// DLDataTypeCode.
enum DLDataTypeCode : uint8_t {
  kDLInt = 0,
  kDLUInt = 1,
  kDLFloat = 2,
};

struct DLDataType {
  uint8_t code;
  uint8_t bits;
  uint16_t lanes;
};

struct DLTensor {
  void* data;
  DLDevice device;
  int32_t ndim;
  DLDataType dtype;
  int64_t* shape;
  int64_t* strides;  // null: compact row-major
  uint64_t byte_offset;
};

struct DLManagedTensor {
  DLTensor dl_tensor;
  void* manager_ctx;
  void (*deleter)(DLManagedTensor* self);
};

// What a buffer shares: its memory, the device it is on, its element type and shape.
struct DlpackExport {
  void* data = nullptr;
  DLDevice device{kDLCPU, 0};
  DLDataType dtype{kDLUInt, 32, 1};
  int32_t ndim = 1;
  int64_t shape[2] = {0, 0};
};

// A "dltensor" capsule of `e` that holds `owner` (the Python buffer object) until the consumer
// calls the deleter, or until the capsule is dropped unconsumed.
py::capsule make_dlpack_capsule(const DlpackExport& e, py::object owner);

}  // namespace masav::python
