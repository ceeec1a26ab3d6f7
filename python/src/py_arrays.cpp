#include "python/src/py_arrays.h"

#include <fmt/format.h>

#include <cmath>
#include <cstring>
#include <span>

namespace masav::python {
namespace {

std::string shape_text(const py::array& a) {
  std::string s = "(";
  for (py::ssize_t d = 0; d < a.ndim(); ++d) s += fmt::format("{}{}", d ? ", " : "", a.shape(d));
  return s + (a.ndim() == 1 ? ",)" : ")");
}

std::string dtype_text(const py::array& a) {
  return py::str(a.dtype()).cast<std::string>();
}

bool is_dtype(const py::array& a, const py::dtype& d) {
  return a.dtype().is(d) || a.dtype().attr("__eq__")(d).cast<bool>();
}

// The allowed dtypes of a buffer kind, as an error names them.
const char* allowed_dtypes(ElemKind kind) {
  switch (kind) {
    case ElemKind::u32:
      return "uint32";
    case ElemKind::i32:
      return "int32";
    case ElemKind::f32:
      return "float32";
    case ElemKind::real:
    case ElemKind::real4:
      return "float32 or float64";
  }
  return "?";
}

bool dtype_fits(const py::array& a, ElemKind kind) {
  switch (kind) {
    case ElemKind::u32:
      return is_dtype(a, py::dtype::of<uint32_t>());
    case ElemKind::i32:
      return is_dtype(a, py::dtype::of<int32_t>());
    case ElemKind::f32:
      return is_dtype(a, py::dtype::of<float>());
    case ElemKind::real:
    case ElemKind::real4:
      return is_dtype(a, py::dtype::of<float>()) || is_dtype(a, py::dtype::of<double>());
  }
  return false;
}

// The first value that is NaN or infinite, as "element i" or "element (i, c)".
template <class F>
std::optional<std::string> first_non_finite(const F* v, size_t scalars, bool rows_of_4) {
  for (size_t i = 0; i < scalars; ++i)
    if (!std::isfinite(v[i]))
      return fmt::format("element {} is {}",
                         rows_of_4 ? fmt::format("({}, {})", i / 4, i % 4) : std::to_string(i),
                         double(v[i]));
  return std::nullopt;
}

}  // namespace

py::dtype dtype_of(ElemKind kind, size_t real_bytes) {
  switch (kind) {
    case ElemKind::u32:
      return py::dtype::of<uint32_t>();
    case ElemKind::i32:
      return py::dtype::of<int32_t>();
    case ElemKind::f32:
      return py::dtype::of<float>();
    case ElemKind::real:
    case ElemKind::real4:
      return real_bytes == 8 ? py::dtype::of<double>() : py::dtype::of<float>();
  }
  return py::dtype::of<uint32_t>();
}

std::vector<py::ssize_t> shape_of(ElemKind kind, size_t count) {
  if (kind == ElemKind::real4) return {py::ssize_t(count), 4};
  return {py::ssize_t(count)};
}

size_t checked_elements(const py::array& a, ElemKind kind, std::string_view what, bool reads,
                        bool writes) {
  if (!dtype_fits(a, kind))
    bad_argument(what, "dtype", dtype_text(a),
                 fmt::format("{} for a {} buffer (convert with .astype)", allowed_dtypes(kind),
                             elem_kind_name(kind)));
  const bool rows = kind == ElemKind::real4;
  if (rows ? (a.ndim() != 2 || a.shape(1) != 4) : a.ndim() != 1)
    bad_argument(what, "shape", shape_text(a),
                 rows ? "(n, 4) for a real4 buffer (x, y, z, w per element)"
                      : fmt::format("(n,) for a {} buffer", elem_kind_name(kind)));
  if (!(a.flags() & py::array::c_style))
    bad_argument(what, "layout", "not C-contiguous",
                 "C-contiguous (pass numpy.ascontiguousarray(a))");
  const size_t n = size_t(a.shape(0));
  if (n == 0)
    bad_argument(what, "n", "0 elements", "at least 1 element (masav buffers are never empty)");
  if (writes && !a.writeable())
    bad_argument(what, "writeable", "False", "a writable array (the kernel writes it)");
  if (reads) {
    const size_t scalars = size_t(a.size());
    std::optional<std::string> bad;
    if (is_dtype(a, py::dtype::of<float>()))
      bad = first_non_finite(static_cast<const float*>(a.data()), scalars, rows);
    else if (is_dtype(a, py::dtype::of<double>()))
      bad = first_non_finite(static_cast<const double*>(a.data()), scalars, rows);
    if (bad) bad_argument(what, "value", *bad, "finite (no NaN or infinity)");
  }
  return n;
}

ElemKind kind_of_array(const py::array& a, std::string_view what) {
  const bool f32 = is_dtype(a, py::dtype::of<float>());
  const bool f64 = is_dtype(a, py::dtype::of<double>());
  if (a.ndim() == 2 && a.shape(1) == 4 && (f32 || f64)) return ElemKind::real4;
  if (is_dtype(a, py::dtype::of<uint32_t>())) return ElemKind::u32;
  if (is_dtype(a, py::dtype::of<int32_t>())) return ElemKind::i32;
  if (f32) return ElemKind::f32;
  if (f64) return ElemKind::real;
  bad_argument(what, "dtype", dtype_text(a),
               "uint32, int32, float32 or float64 ((n,), or (n, 4) for real4)");
}

void upload_array(PyBackend& pb, PyBuffer& b, const py::array& a, std::string_view what,
                  bool finite) {
  const ElemKind kind = b.kind();
  const size_t n = checked_elements(a, kind, what, finite, false);
  if (n != b.count())
    bad_argument(what, "n", fmt::format("{} elements", n),
                 fmt::format("the buffer's {} elements", b.count()));
  const bool real = kind == ElemKind::real || kind == ElemKind::real4;
  const void* src = a.data();
  const size_t bytes = size_t(a.nbytes());
  const bool f64 = a.itemsize() == 8;
  // The copy runs without the GIL; `a` (held by the caller) keeps its memory alive.
  without_gil(pb, [&](Backend& be) {
    if (!real || (f64 ? 8u : 4u) == be.real_bytes()) {
      be.upload_bytes(b.impl(), src, bytes, 0);
      return;
    }
    // A float width other than the backend's: the typed uploads convert.
    if (kind == ElemKind::real) {
      auto& t = b.typed<Real>(what);
      if (f64)
        be.upload(t, std::span(static_cast<const double*>(src), n));
      else
        be.upload(t, std::span(static_cast<const float*>(src), n));
    } else {
      auto& t = b.typed<Real4>(what);
      static_assert(sizeof(Vec4d) == 32 && sizeof(Vec4f) == 16);
      if (f64)
        be.upload(t, std::span(static_cast<const Vec4d*>(src), n));
      else
        be.upload(t, std::span(static_cast<const Vec4f*>(src), n));
    }
  });
}

py::array download_array(PyBackend& pb, PyBuffer& b) {
  const size_t n = b.count();
  py::array out(dtype_of(b.kind(), pb.backend->real_bytes()), shape_of(b.kind(), n));
  void* dst = out.mutable_data();
  const size_t bytes = size_t(out.nbytes());
  without_gil(pb, [&](Backend& be) { be.download_bytes(b.impl(), dst, bytes, 0); });
  return out;
}

void download_into(PyBackend& pb, PyBuffer& b, py::array a, std::string_view what) {
  const ElemKind kind = b.kind();
  const size_t n = checked_elements(a, kind, what, false, true);
  if (n != b.count())
    bad_argument(what, "n", fmt::format("{} elements", n),
                 fmt::format("the buffer's {} elements", b.count()));
  const bool real = kind == ElemKind::real || kind == ElemKind::real4;
  void* dst = a.mutable_data();
  const size_t bytes = size_t(a.nbytes());
  const bool f64 = a.itemsize() == 8;
  without_gil(pb, [&](Backend& be) {
    if (!real || (f64 ? 8u : 4u) == be.real_bytes()) {
      be.download_bytes(b.impl(), dst, bytes, 0);
      return;
    }
    // Another float width than the backend's: through the typed download (doubles), rounded
    // or widened into the array.
    std::vector<double> v;
    if (kind == ElemKind::real) {
      v = be.download(b.typed<Real>(what));
    } else {
      const auto w = be.download(b.typed<Real4>(what));
      v.resize(4 * w.size());
      std::memcpy(v.data(), static_cast<const void*>(w.data()), v.size() * sizeof(double));
    }
    if (f64) {
      std::memcpy(dst, v.data(), v.size() * sizeof(double));
    } else {
      auto* f = static_cast<float*>(dst);
      for (size_t i = 0; i < v.size(); ++i) f[i] = float(v[i]);
    }
  });
}

}  // namespace masav::python
