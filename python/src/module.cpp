// The extension module masav._masav; python/masav/__init__.py re-exports it as `masav`.
#include "python/src/py_core.h"

PYBIND11_MODULE(_masav, m) {
  using namespace masav::python;
  m.doc() =
      "masav: one kernel set on the CPU reference, Vulkan and CUDA, cross-checked; the SPH "
      "fluid, the electron cloud and volume raymarching on numpy arrays.";
  m.attr("__version__") = MASAV_VERSION_STRING;
  bind_errors(m);
  BackendClass backend = bind_backends(m);
  bind_buffers(m, backend);
  bind_params(m);
  bind_kernels(m, backend);
  bind_scenes(m);
  bind_scene_render(m);
  bind_verify(m);
  bind_sph(m);
  bind_volume(m);
  bind_atom(m);
}
