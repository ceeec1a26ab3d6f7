#pragma once
/// \file
/// The kernel set. Each kernel of engine/kernels/kernels.inc is a method of `masav::Backend`,
/// `backend.name(params, buffers...)`, with its parameter struct (e.g. `RadixSortParams`) and
/// typed buffers (`Buffer<uint32_t>`, `Buffer<Real>`, `Buffer<Real4>`; `Real` is fp64 on the CPU
/// reference and fp32 on the GPUs). Every call checks its parameters and buffers the same way on
/// every backend; `KernelId` names a kernel.
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "engine/kernels/backend.h"
#include "engine/kernels/kernel_id.h"

namespace masav {

/// The names of every kernel, in the order of the kernel list.
std::vector<std::string> kernel_list();

/// The kernel called `name`, or nothing.
std::optional<KernelId> kernel_by_name(std::string_view name);

/// A new buffer of `backend` holding `values` (an upload; `T` is the buffer's element type,
/// `V` the host's, e.g. `to_device<Real4>(b, std::span<const Vec4d>(v))`).
template <class T, class V>
Buffer<T> to_device(Backend& backend, std::span<const V> values,
                    std::string_view label = "host data") {
  Buffer<T> b = backend.template create<T>(values.size(), label);
  if (!values.empty()) backend.upload(b, values);
  return b;
}

/// A buffer's values on the host (a download; waits for the work before it).
template <class T>
auto to_host(Backend& backend, const Buffer<T>& buffer) {
  return backend.download(buffer);
}

}  // namespace masav
