// masav.Error: the one exception type, carrying the message the command line prints (the
// engine's masav::Error text) and its parts as attributes: backend, kernel (or the field's
// place), problem, remedy.
#include <fmt/format.h>

#include "python/src/py_core.h"

namespace masav::python {
namespace {

PyObject* g_error_type = nullptr;  // masav.Error, owned by the module for the process's life

void raise_error(const Error& e) {
  py::object err =
      py::reinterpret_steal<py::object>(PyObject_CallFunction(g_error_type, "s", e.what()));
  if (!err) return;  // the call set its own error
  err.attr("backend") = e.backend();
  err.attr("kernel") = e.kernel();
  err.attr("problem") = e.problem();
  err.attr("remedy") = e.remedy();
  PyErr_SetObject(g_error_type, err.ptr());
}

}  // namespace

void bad_argument(std::string_view where, std::string_view field, std::string_view value,
                  std::string_view allowed) {
  throw_invalid(where, field, value, allowed);
}

void bind_errors(py::module_& m) {
  g_error_type = PyErr_NewExceptionWithDoc(
      "masav.Error",
      "Every error masav raises: the message names the backend and kernel (or the argument), "
      "what went wrong and the remedy, as the masav command line prints it.",
      PyExc_Exception, nullptr);
  m.add_object("Error", py::handle(g_error_type));
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const Error& e) {
      raise_error(e);
    }
  });
}

}  // namespace masav::python
