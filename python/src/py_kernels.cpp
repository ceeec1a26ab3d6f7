// Every kernel of engine/kernels/kernels.inc as a method of masav.Backend, expanded from the list
// (a kernel added there is in Python with no line here):
//   backend.radix_sort(masav.RadixSortParams(n=n), keys, values)
// Each buffer argument is a masav.Buffer of this backend, a numpy array or None (optional
// buffers only). An array is checked (py_arrays.h) and copied into a buffer of the kernel's
// element type; the arrays the kernel writes get the results back after the call, in place.
// The call itself is the contract's public method, so the parameters and buffers are validated
// there with the messages every backend gives, and the GIL is released while it runs.
#include <fmt/format.h>
#include <pybind11/stl.h>

#include <deque>

#include "python/src/py_arrays.h"
#include "python/src/py_casters.h"

namespace masav::python {
namespace {

// What each access of kernels.inc asks of an argument, and the C++ type the method takes.
template <bool Optional, bool Reads, bool Writes, bool Any>
struct Access {
  static constexpr bool optional = Optional, reads = Reads, writes = Writes, any = Any;
};
using Access_in = Access<false, true, false, false>;
using Access_out = Access<false, false, true, false>;
using Access_inout = Access<false, true, true, false>;
using Access_opt_in = Access<true, true, false, false>;
using Access_opt_out = Access<true, false, true, false>;
using Access_opt_inout = Access<true, true, true, false>;
using Access_any_in = Access<false, true, false, true>;
using Access_any_out = Access<false, false, true, true>;

// One call's buffer arguments: the temporary buffers of its arrays and the arrays to fill after.
class Args {
 public:
  Args(BackendRef b, const char* kernel) : backend_(std::move(b)), kernel_(kernel) {}

  // The argument `name` as the kernel method takes it (see Access).
  template <class A, class E>
  decltype(auto) take(const char* name, const py::object& o) {
    if constexpr (A::any) {
      return any_buffer<A>(name, o).impl();
    } else if constexpr (A::optional) {
      using Ptr = std::conditional_t<A::writes, Buffer<E>*, const Buffer<E>*>;
      if (o.is_none()) return Ptr(nullptr);
      return Ptr(&buffer<A>(name, o, elem_kind_of<E>()).template typed<E>(where(name)));
    } else {
      using Ref = std::conditional_t<A::writes, Buffer<E>&, const Buffer<E>&>;
      return Ref(buffer<A>(name, o, elem_kind_of<E>()).template typed<E>(where(name)));
    }
  }

  // The results into the arrays the kernel wrote.
  void write_back() {
    for (auto& [array, buf] : back_) download_into(*backend_, *buf, array, "result");
  }

 private:
  std::string where(const char* name) const { return fmt::format("{} {}", kernel_, name); }

  template <class A>
  PyBuffer& buffer(const char* name, const py::object& o, ElemKind kind) {
    if (o.is_none())
      bad_argument(kernel_, name, "None",
                   fmt::format("a masav.Buffer or numpy array of {} (the kernel needs it)",
                               elem_kind_name(kind)));
    if (py::isinstance<PyBuffer>(o)) return o.cast<PyBuffer&>();
    if (!py::isinstance<py::array>(o))
      bad_argument(kernel_, name, py::str(py::type::of(o).attr("__name__")).cast<std::string>(),
                   fmt::format("a masav.Buffer or numpy array of {}", elem_kind_name(kind)));
    return from_array<A>(name, o.cast<py::array>(), kind);
  }

  template <class A>
  PyBuffer& any_buffer(const char* name, const py::object& o) {
    if (o.is_none())
      bad_argument(kernel_, name, "None", "a masav.Buffer or numpy array (the kernel needs it)");
    if (!py::isinstance<PyBuffer>(o) && py::isinstance<py::array>(o)) {
      const auto a = o.cast<py::array>();
      return from_array<A>(name, a, kind_of_array(a, where(name)));
    }
    return buffer<A>(name, o, ElemKind::u32);
  }

  template <class A>
  PyBuffer& from_array(const char* name, const py::array& a, ElemKind kind) {
    const std::string what = where(name);
    const size_t n = checked_elements(a, kind, what, A::reads, A::writes);
    PyBuffer& b = temps_.emplace_back(backend_, without_gil(*backend_, [&](Backend& be) {
                                        return create_any(be, kind, n, what);
                                      }));
    // Written buffers are uploaded too: kernels.inc's access says what a kernel must be given,
    // not all it reads (radix_sort's values are opt_out and moved with the keys).
    upload_array(*backend_, b, a, what, A::reads);
    if (A::writes) back_.emplace_back(a, &b);
    return b;
  }

  BackendRef backend_;
  const char* kernel_;
  std::deque<PyBuffer> temps_;  // stable addresses: the method holds references into it
  std::vector<std::pair<py::array, PyBuffer*>> back_;
};

}  // namespace

// The element type a buffer of each access names in kernels.inc (`any` for any element type).
#define MASAV_PY_ELEM_in(elem) elem
#define MASAV_PY_ELEM_out(elem) elem
#define MASAV_PY_ELEM_inout(elem) elem
#define MASAV_PY_ELEM_opt_in(elem) elem
#define MASAV_PY_ELEM_opt_out(elem) elem
#define MASAV_PY_ELEM_opt_inout(elem) elem
#define MASAV_PY_ELEM_any_in(elem) void
#define MASAV_PY_ELEM_any_out(elem) void

#define MASAV_PY_PARAM(d, access, elem, name, binding) , const py::object& name
#define MASAV_PY_TAKE(d, access, elem, name, binding) \
  auto&& name##_ = args.take<Access_##access, MASAV_PY_ELEM_##access(elem)>(#name, name);
#define MASAV_PY_CALL_ARG(d, access, elem, name, binding) , name##_
#define MASAV_PY_ARG(d, access, elem, name, binding) , py::arg(#name) = py::none()
#define MASAV_PY_DOC(d, access, elem, name, binding) ", " #name " (" #access " " #elem ")"
#define MASAV_PY_INFO(d, access, elem, name, binding) \
  buffers.append(py::make_tuple(#name, #access, #elem));

void bind_kernels(py::module_& m, BackendClass& cls) {
#define MASAV_KERNEL(name, Params, items, ...) \
  cls.def(                                                                                     \
      #name,                                                                                   \
      [](const BackendRef& self, const Params& p MASAV_PP_EACH(MASAV_PY_PARAM, _, __VA_ARGS__)) { \
        Args args(self, #name);                                                                \
        MASAV_PP_EACH(MASAV_PY_TAKE, _, __VA_ARGS__)                                           \
        without_gil(*self, [&](Backend& be) {                                                  \
          be.name(p MASAV_PP_EACH(MASAV_PY_CALL_ARG, _, __VA_ARGS__));                         \
        });                                                                                    \
        args.write_back();                                                                     \
      },                                                                                       \
      py::arg("p") MASAV_PP_EACH(MASAV_PY_ARG, _, __VA_ARGS__),                                \
      "The kernel " #name "(p: " #Params MASAV_PP_EACH(MASAV_PY_DOC, _, __VA_ARGS__)          \
      "). Buffers: masav.Buffer or numpy arrays (copied in, and back where written).");
#include "engine/kernels/kernels.inc"
#undef MASAV_KERNEL

  m.def(
      "kernels",
      [] {
        py::list out;
#define MASAV_KERNEL(name, Params, items, ...)           \
  {                                                      \
    py::list buffers;                                    \
    MASAV_PP_EACH(MASAV_PY_INFO, _, __VA_ARGS__)         \
    out.append(py::make_tuple(#name, #Params, buffers)); \
  }
#include "engine/kernels/kernels.inc"
#undef MASAV_KERNEL
        return out;
      },
      "The kernel list: (name, parameter class, [(buffer, access, element type)]) per kernel, "
      "in the order of kernels.inc.");
}

}  // namespace masav::python
