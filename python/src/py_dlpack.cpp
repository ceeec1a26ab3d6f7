#include "python/src/py_dlpack.h"

namespace masav::python {
namespace {

// The managed tensor with the shape it points to and the reference to its owner.
struct Managed {
  DLManagedTensor tensor{};
  int64_t shape[2] = {0, 0};
  PyObject* owner = nullptr;
};

// The consumer may call it from any thread, with or without the GIL.
void delete_managed(DLManagedTensor* self) {
  auto* m = static_cast<Managed*>(self->manager_ctx);
  PyGILState_STATE gil = PyGILState_Ensure();
  Py_XDECREF(m->owner);
  PyGILState_Release(gil);
  delete m;
}

// A capsule still named "dltensor" when it dies was never consumed: the tensor is ours to free.
// A consumer renames it "used_dltensor" and calls the deleter itself.
void capsule_destructor(PyObject* capsule) {
  if (PyCapsule_IsValid(capsule, "dltensor")) {
    auto* t = static_cast<DLManagedTensor*>(PyCapsule_GetPointer(capsule, "dltensor"));
    if (t && t->deleter) t->deleter(t);
  } else {
    PyErr_Clear();  // PyCapsule_IsValid sets no error, but a renamed capsule's lookups may
  }
}

}  // namespace

py::capsule make_dlpack_capsule(const DlpackExport& e, py::object owner) {
  auto* m = new Managed;
  m->shape[0] = e.shape[0];
  m->shape[1] = e.shape[1];
  m->owner = owner.release().ptr();
  DLTensor& t = m->tensor.dl_tensor;
  t.data = e.data;
  t.device = e.device;
  t.ndim = e.ndim;
  t.dtype = e.dtype;
  t.shape = m->shape;
  t.strides = nullptr;
  t.byte_offset = 0;
  m->tensor.manager_ctx = m;
  m->tensor.deleter = &delete_managed;
  PyObject* cap = PyCapsule_New(&m->tensor, "dltensor", &capsule_destructor);
  if (!cap) {
    delete_managed(&m->tensor);
    throw py::error_already_set();
  }
  return py::reinterpret_steal<py::capsule>(cap);
}

}  // namespace masav::python
