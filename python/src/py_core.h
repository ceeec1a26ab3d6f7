#pragma once
// What the binding's files share: the backend and buffer objects Python holds, and the function
// each file adds its part of the module with (module.cpp calls them in order).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <variant>

#include "engine/core/error.h"
#include "engine/core/tuning.h"
#include "engine/kernels/backend.h"

namespace masav::python {

namespace py = pybind11;

// A backend as Python holds it. Its buffers (and simulations) keep it alive. Calls release the
// GIL, so two Python threads could enter one backend together: `mutex` lets one call run at a
// time. It is only ever locked with the GIL released, so a call that takes the GIL back (a
// Ctrl-C poll) cannot deadlock with a thread waiting for the backend.
struct PyBackend {
  std::unique_ptr<Backend> backend;
  std::string requested;  // the name asked for: cpu, vulkan, cuda or auto
  std::mutex mutex;
};
using BackendRef = std::shared_ptr<PyBackend>;

// Runs `work(backend)` without the GIL, one call at a time on that backend.
template <class Work>
decltype(auto) without_gil(PyBackend& b, Work&& work) {
  py::gil_scoped_release nogil;
  std::lock_guard lock(b.mutex);
  return work(*b.backend);
}

using AnyBuffer =
    std::variant<Buffer<uint32_t>, Buffer<int32_t>, Buffer<float>, Buffer<Real>, Buffer<Real4>>;

// A device buffer as Python holds it: its own allocation, or a borrowed Buffer<T> of an object
// that owns it (a simulation's state; `keep` holds that owner alive). A borrowed handle follows
// its owner's buffer, which may change allocations between steps.
class PyBuffer {
 public:
  PyBuffer(BackendRef owner, AnyBuffer own);
  PyBuffer(BackendRef owner, ElemKind kind, void* borrowed_buffer, py::object keep);

  const BackendRef& owner() const { return owner_; }
  ElemKind kind() const { return kind_; }
  BufferImpl& impl();
  size_t count();
  // The handle as the kernel methods take it; `what` names the argument in the error when the
  // element type is not T.
  template <class T>
  Buffer<T>& typed(std::string_view what) {
    if (kind_ != elem_kind_of<T>()) wrong_kind(what, elem_kind_of<T>());
    if (borrowed_) return *static_cast<Buffer<T>*>(borrowed_);
    return std::get<Buffer<T>>(*own_);
  }

 private:
  [[noreturn]] void wrong_kind(std::string_view what, ElemKind wanted) const;

  BackendRef owner_;
  ElemKind kind_;
  std::optional<AnyBuffer> own_;
  void* borrowed_ = nullptr;
  py::object keep_;
};

// A numpy view of the buffer's host memory that keeps `base` alive (the CPU reference's
// buffers only; elsewhere a masav.Error that points to download()).
py::array host_view(PyBuffer& b, py::handle base);

// A new buffer of `count` elements of `kind` on `b` (count 0 is refused by name).
AnyBuffer create_any(Backend& b, ElemKind kind, size_t count, const std::string& label);

// The element kinds by the names Python uses: "u32", "i32", "f32", "real", "real4".
ElemKind parse_kind(std::string_view name);

// A masav::Error for a bad argument of a Python call: "where: invalid field = value (remedy:
// field must be allowed)", the message every masav input error has.
[[noreturn]] void bad_argument(std::string_view where, std::string_view field,
                               std::string_view value, std::string_view allowed);

// The parts of the module, one per file. The kernels are methods of masav.Backend.
using BackendClass = py::class_<PyBackend, BackendRef>;
// The tuning options of a `tune` argument: a dict {"cpu.threads": 2}, a list of
// "key=value" strings, or None (all automatic). Refuses a bare string by name.
Tuning tuning_of(const py::object& tune, std::string_view where = "masav.Backend");

void bind_errors(py::module_& m);
BackendClass bind_backends(py::module_& m);
void bind_buffers(py::module_& m, BackendClass& backend);
void bind_params(py::module_& m);
void bind_kernels(py::module_& m, BackendClass& backend);
void bind_verify(py::module_& m);
void bind_sph(py::module_& m);
void bind_volume(py::module_& m);
void bind_atom(py::module_& m);
void bind_scenes(py::module_& m);
void bind_scene_render(py::module_& m);

}  // namespace masav::python
