#pragma once
// numpy arrays to and from device buffers. An array a buffer reads must have the buffer's
// element type (u32 uint32, i32 int32, f32 float32, real and real4 float32 or float64), its
// shape ((n,), or (n, 4) for real4), be C-contiguous, hold at least one element, and, for floats,
// hold only finite values; anything else is a masav.Error naming the argument, what it got and
// what is allowed. Arrays a buffer writes must also be writable.
#include <string>
#include <string_view>

#include "python/src/py_core.h"

namespace masav::python {

// The numpy dtype of a buffer's elements on a backend whose Real is `real_bytes` wide.
py::dtype dtype_of(ElemKind kind, size_t real_bytes);
// The shape of `count` elements: (count,), or (count, 4) for real4.
std::vector<py::ssize_t> shape_of(ElemKind kind, size_t count);

// The elements `a` holds for a buffer of `kind`, after every check above (`reads`: the values
// are read, so floats must be finite; `writes`: the array must be writable).
size_t checked_elements(const py::array& a, ElemKind kind, std::string_view what, bool reads,
                        bool writes);
// The element kind an array of this dtype and shape fills, for a buffer of any element type
// (gather's src and dst, Backend.upload): uint32 u32, int32 i32, float32 (n,) f32, float64 (n,)
// real, float32 or float64 (n, 4) real4.
ElemKind kind_of_array(const py::array& a, std::string_view what);

// Copies `a` (checked) into the whole buffer `b` of `backend`, converting floats to the backend's
// precision; `a` must have exactly the buffer's element count.
// The checks run with the GIL, the copy without it (and with the backend's lock). `finite`:
// refuse NaN and infinities (the values are read).
void upload_array(PyBackend& backend, PyBuffer& b, const py::array& a, std::string_view what,
                  bool finite = true);
// The buffer's contents as a new array of dtype_of(kind, real_bytes).
py::array download_array(PyBackend& backend, PyBuffer& b);
// The buffer's contents into `a` (checked, writable, the buffer's element count).
void download_into(PyBackend& backend, PyBuffer& b, py::array a, std::string_view what);

}  // namespace masav::python
