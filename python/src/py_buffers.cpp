// masav.Buffer: a typed device buffer of one backend. upload() and download() copy to and from
// numpy; on the CPU reference numpy() is a view of the buffer's own memory (no copy: a write
// through it is what the next kernel reads); __dlpack__ shares it with any DLPack consumer
// (numpy.from_dlpack on the CPU, CuPy or PyTorch on CUDA), and CUDA buffers also give
// __cuda_array_interface__.
#include <fmt/format.h>
#include <pybind11/stl.h>

#include <type_traits>

#include "engine/cpu/cpu_backend.h"
#include "python/src/cuda_memory.h"
#include "python/src/py_arrays.h"
#include "python/src/py_dlpack.h"

namespace masav::python {
namespace {

ElemKind kind_of_buffer(const AnyBuffer& b) {
  return std::visit([](const auto& t) { return t.impl().kind(); }, b);
}

// The buffer's elements in host memory (the CPU reference's), or null.
void* host_memory(BufferImpl& b) {
  auto* c = dynamic_cast<cpu::CpuBuffer*>(&b);
  return c ? c->data() : nullptr;
}

std::string where_it_lives(PyBuffer& b) {
  return fmt::format("the {} backend keeps its buffers on its device ({})",
                     b.owner()->backend->name(), b.owner()->backend->caps().device_name);
}

DLDataType dl_dtype(ElemKind kind, size_t real_bytes) {
  switch (kind) {
    case ElemKind::u32:
      return {kDLUInt, 32, 1};
    case ElemKind::i32:
      return {kDLInt, 32, 1};
    case ElemKind::f32:
      return {kDLFloat, 32, 1};
    case ElemKind::real:
    case ElemKind::real4:
      return {kDLFloat, uint8_t(8 * real_bytes), 1};
  }
  return {kDLUInt, 32, 1};
}

// What the buffer shares without a copy: host memory (CPU) or device memory (CUDA).
DlpackExport export_of(PyBuffer& b) {
  Backend& be = *b.owner()->backend;
  DlpackExport e;
  e.dtype = dl_dtype(b.kind(), be.real_bytes());
  e.shape[0] = int64_t(b.count());
  e.ndim = b.kind() == ElemKind::real4 ? 2 : 1;
  e.shape[1] = 4;
  if ((e.data = host_memory(b.impl()))) {
    e.device = {kDLCPU, 0};
  } else if ((e.data = cuda_pointer(b.impl()))) {
    e.device = {kDLCUDA, cuda_device_of(e.data)};
  } else {
    throw Error(be.name(), "__dlpack__",
                fmt::format("buffer '{}' cannot be shared without a copy: {}", b.impl().label(),
                            where_it_lives(b)),
                "call download() for a numpy copy");
  }
  return e;
}

}  // namespace

py::array host_view(PyBuffer& b, py::handle self) {
  void* data = host_memory(b.impl());
  if (!data)
    throw Error(b.owner()->backend->name(), "numpy",
                fmt::format("buffer '{}' has no host memory to view: {}", b.impl().label(),
                            where_it_lives(b)),
                "call download() for a copy (views are for the CPU backend)");
  return py::array(dtype_of(b.kind(), b.owner()->backend->real_bytes()),
                   shape_of(b.kind(), b.count()), {}, data, self);
}

namespace {

const char* typestr(ElemKind kind, size_t real_bytes) {
  switch (kind) {
    case ElemKind::u32:
      return "<u4";
    case ElemKind::i32:
      return "<i4";
    case ElemKind::f32:
      return "<f4";
    default:
      return real_bytes == 8 ? "<f8" : "<f4";
  }
}

std::unique_ptr<PyBuffer> new_buffer(const BackendRef& b, const std::string& kind, size_t count,
                                     const std::string& label) {
  const ElemKind k = parse_kind(kind);
  AnyBuffer any = without_gil(*b, [&](Backend& be) {
    AnyBuffer a = create_any(be, k, count, label.empty() ? "python buffer" : label);
    std::visit([&](auto& t) { be.fill_u32(t.impl(), 0); }, a);
    return a;
  });
  return std::make_unique<PyBuffer>(b, std::move(any));
}

std::unique_ptr<PyBuffer> uploaded(const BackendRef& b, const py::array& a,
                                   const std::optional<std::string>& kind,
                                   const std::string& label) {
  const ElemKind k = kind ? parse_kind(*kind) : kind_of_array(a, "Backend.upload");
  const size_t n = checked_elements(a, k, "Backend.upload", true, false);
  auto buf = std::make_unique<PyBuffer>(b, without_gil(*b, [&](Backend& be) {
                                          return create_any(
                                              be, k, n, label.empty() ? "python upload" : label);
                                        }));
  upload_array(*b, *buf, a, "Backend.upload");
  return buf;
}

}  // namespace

PyBuffer::PyBuffer(BackendRef owner, AnyBuffer own)
    : owner_(std::move(owner)), kind_(kind_of_buffer(own)), own_(std::move(own)) {}

PyBuffer::PyBuffer(BackendRef owner, ElemKind kind, void* borrowed_buffer, py::object keep)
    : owner_(std::move(owner)), kind_(kind), borrowed_(borrowed_buffer), keep_(std::move(keep)) {}

BufferImpl& PyBuffer::impl() {
  auto of = [this](auto tag) -> BufferImpl* {
    auto& t = typed<typename decltype(tag)::type>("buffer");
    return t.valid() ? &t.impl() : nullptr;
  };
  BufferImpl* impl = nullptr;
  switch (kind_) {
    case ElemKind::u32:
      impl = of(std::type_identity<uint32_t>{});
      break;
    case ElemKind::i32:
      impl = of(std::type_identity<int32_t>{});
      break;
    case ElemKind::f32:
      impl = of(std::type_identity<float>{});
      break;
    case ElemKind::real:
      impl = of(std::type_identity<Real>{});
      break;
    case ElemKind::real4:
      impl = of(std::type_identity<Real4>{});
      break;
  }
  if (!impl)
    throw Error(owner_->backend->name(), "buffer", "the buffer is empty (its owner released it)",
                "take the buffer again from its owner");
  return *impl;
}

size_t PyBuffer::count() {
  return impl().count();
}

void PyBuffer::wrong_kind(std::string_view what, ElemKind wanted) const {
  bad_argument(what, "element type", elem_kind_name(kind_),
               fmt::format("{} (this argument's element type)", elem_kind_name(wanted)));
}

AnyBuffer create_any(Backend& b, ElemKind kind, size_t count, const std::string& label) {
  if (count == 0)
    bad_argument("masav.Buffer", "count", "0", "at least 1 (masav buffers are never empty)");
  check_fits(b, kind, count, "masav.Buffer", label);
  switch (kind) {
    case ElemKind::u32:
      return b.create<uint32_t>(count, label);
    case ElemKind::i32:
      return b.create<int32_t>(count, label);
    case ElemKind::f32:
      return b.create<float>(count, label);
    case ElemKind::real:
      return b.create<Real>(count, label);
    case ElemKind::real4:
      return b.create<Real4>(count, label);
  }
  return b.create<uint32_t>(count, label);
}

ElemKind parse_kind(std::string_view name) {
  for (ElemKind k : {ElemKind::u32, ElemKind::i32, ElemKind::f32, ElemKind::real, ElemKind::real4})
    if (name == elem_kind_name(k)) return k;
  bad_argument("masav.Buffer", "kind", std::string(name), "u32, i32, f32, real or real4");
}

void bind_buffers(py::module_& m, BackendClass& backend) {
  py::class_<PyBuffer>(m, "Buffer",
                       "A typed buffer of one backend: kind u32, i32, f32, real or real4 (real: "
                       "float64 on the CPU reference, float32 on GPUs; real4: (n, 4)).")
      .def_property_readonly("kind", [](PyBuffer& b) { return elem_kind_name(b.kind()); })
      .def_property_readonly("backend", [](PyBuffer& b) { return b.owner(); })
      .def_property_readonly("label", [](PyBuffer& b) { return b.impl().label(); })
      .def_property_readonly("nbytes", [](PyBuffer& b) { return b.impl().bytes(); })
      .def_property_readonly(
          "dtype", [](PyBuffer& b) { return dtype_of(b.kind(), b.owner()->backend->real_bytes()); })
      .def_property_readonly("shape",
                             [](PyBuffer& b) {
                               auto s = shape_of(b.kind(), b.count());
                               return py::tuple(py::cast(s));
                             })
      .def("__len__", &PyBuffer::count)
      .def(
          "upload",
          [](PyBuffer& b, const py::array& a) { upload_array(*b.owner(), b, a, "Buffer.upload"); },
          py::arg("array"), "Copies `array` (the buffer's dtype and element count) into it.")
      .def(
          "download",
          [](PyBuffer& b, const std::optional<py::array>& out) -> py::array {
            if (!out) return download_array(*b.owner(), b);
            download_into(*b.owner(), b, *out, "out");
            return *out;
          },
          py::arg("out") = py::none(),
          "The contents as a new numpy array (the backend's precision), or into `out`.")
      .def(
          "fill",
          [](PyBuffer& b, uint32_t word) {
            without_gil(*b.owner(), [&](Backend& be) { be.fill_u32(b.impl(), word); });
          },
          py::arg("word") = 0, "Sets every 32-bit word to `word` (0: every element zero).")
      .def(
          "numpy", [](py::object self) { return host_view(self.cast<PyBuffer&>(), self); },
          "A numpy view of the buffer's memory, no copy (CPU backend only; it stays valid while "
          "the buffer lives, and a write through it is what the next kernel reads).")
      .def(
          "__dlpack__",
          // stream: work queued on the backend finishes first, so the data is ready on any
          // stream. max_version, dl_device, copy (DLPack 1.0's keywords): the unversioned
          // capsule every consumer takes, of the buffer's own memory.
          [](py::object self, py::object /*stream*/, py::kwargs /*newer keywords*/) {
            PyBuffer& b = self.cast<PyBuffer&>();
            without_gil(*b.owner(), [](Backend& be) { be.finish(); });
            return make_dlpack_capsule(export_of(b), self);
          },
          py::arg("stream") = py::none())
      .def("__dlpack_device__",
           [](PyBuffer& b) {
             if (host_memory(b.impl())) return py::make_tuple(int(kDLCPU), 0);
             if (void* p = cuda_pointer(b.impl()))
               return py::make_tuple(int(kDLCUDA), cuda_device_of(p));
             return py::make_tuple(int(kDLVulkan), 0);
           })
      .def_property_readonly(
          "__cuda_array_interface__",
          [](PyBuffer& b) {
            void* p = cuda_pointer(b.impl());
            if (!p)
              throw py::attribute_error(fmt::format(
                  "__cuda_array_interface__: buffer '{}' is on the {} backend, not CUDA",
                  b.impl().label(), b.owner()->backend->name()));
            without_gil(*b.owner(), [](Backend& be) { be.finish(); });
            py::dict d;
            auto shape = shape_of(b.kind(), b.count());
            d["shape"] = py::tuple(py::cast(shape));
            d["typestr"] = typestr(b.kind(), b.owner()->backend->real_bytes());
            d["data"] = py::make_tuple(reinterpret_cast<uintptr_t>(p), false);
            d["version"] = 3;
            d["strides"] = py::none();
            d["stream"] = py::none();  // finished above: no synchronisation needed
            return d;
          })
      .def("__repr__", [](PyBuffer& b) {
        return fmt::format("masav.Buffer({}, {} elements, '{}' on {})", elem_kind_name(b.kind()),
                           b.count(), b.impl().label(), b.owner()->backend->name());
      });

  backend
      .def("buffer", &new_buffer, py::arg("kind"), py::arg("count"), py::arg("label") = "",
           "A new buffer of `count` elements of `kind` (u32, i32, f32, real, real4), all zero.")
      .def("upload", &uploaded, py::arg("array"), py::arg("kind") = py::none(),
           py::arg("label") = "",
           "A new buffer holding `array`; kind from its dtype and shape unless given.");
}

}  // namespace masav::python
