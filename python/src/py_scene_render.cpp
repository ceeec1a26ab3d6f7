// masav.SceneRenderer: a scene file rendered headless frame by frame (masav::SceneRenderer, the
// frames `masav run` writes), each frame an (H, W, 4) uint8 numpy array. Drawing releases the
// GIL; the renderer is used by one thread at a time (its own lock).
#include <pybind11/stl.h>

#include <mutex>
#include <optional>

#include "masav/scene_render.h"
#include "python/src/py_core.h"
#include "registry/scene_file.h"

namespace masav::python {
namespace {

struct PySceneRenderer {
  std::unique_ptr<SceneRenderer> renderer;
  std::mutex mutex;
};

std::unique_ptr<PySceneRenderer> make(const py::object& scene, const std::string& backend,
                                      const std::string& device, const py::object& tune,
                                      const std::optional<std::string>& cache_dir,
                                      bool validation, const std::optional<std::string>& loader,
                                      const std::string& render_device) {
  scene::SceneFile file = py::isinstance<py::str>(scene)
                              ? scene::load_scene_file(scene.cast<std::string>())
                              : scene.cast<scene::SceneFile>();
  BackendOptions o;
  o.name = backend;
  o.device = device;
  o.tuning = tuning_of(tune, "masav.SceneRenderer");
  o.cache_dir = cache_dir.value_or("");
  o.vulkan_validation = validation;
  if (loader) o.vulkan_loader = *loader;
  auto r = std::make_unique<PySceneRenderer>();
  py::gil_scoped_release nogil;  // devices start and pipelines compile
  r->renderer = std::make_unique<SceneRenderer>(std::move(file), o, RenderOptions{render_device});
  return r;
}

template <class Work>
decltype(auto) locked(PySceneRenderer& r, Work&& work) {
  py::gil_scoped_release nogil;
  std::lock_guard lock(r.mutex);
  return work(*r.renderer);
}

py::array next_frame(PySceneRenderer& r) {
  Frame f = locked(r, [](SceneRenderer& s) { return s.next_frame(); });
  auto* bytes = new std::vector<uint8_t>(std::move(f.rgba));
  py::capsule owner(bytes, [](void* p) { delete static_cast<std::vector<uint8_t>*>(p); });
  return py::array_t<uint8_t>({size_t(f.height), size_t(f.width), size_t(4)}, bytes->data(),
                              owner);
}

}  // namespace

void bind_scene_render(py::module_& m) {
  py::class_<PySceneRenderer>(
      m, "SceneRenderer",
      "A scene (a masav.Scene or a file) played on a compute backend and drawn headless with "
      "Vulkan, frame by frame, as `masav run` draws its PNG frames.")
      .def(py::init(&make), py::arg("scene"), py::arg("backend") = "auto",
           py::arg("device") = "", py::arg("tune") = py::none(), py::arg("cache_dir") = py::none(),
           py::arg("validation") = false, py::arg("loader") = py::none(),
           py::arg("render_device") = "",
           "backend, device, tune, cache_dir, validation, loader: the compute backend, as "
           "masav.Backend takes them. render_device: the Vulkan device that draws when the "
           "backend is not Vulkan (\"\": the best); a Vulkan backend draws on its own device.")
      .def(
          "verify", [](PySceneRenderer& r) { return locked(r, [](SceneRenderer& s) { return s.verify(); }); },
          "The cross-check `masav run` runs first: every kernel of the scene against its "
          "verify.reference.")
      .def("next_frame", &next_frame,
           "The next frame as an (height, width, 4) uint8 RGBA array, rows top first: frame i "
           "shows run.start_time_s + i / run.fps (an SPH scene steps one frame's steps).")
      .def_property_readonly("frames_drawn",
                             [](PySceneRenderer& r) { return r.renderer->frames_drawn(); })
      .def_property_readonly("width", [](PySceneRenderer& r) { return r.renderer->width(); })
      .def_property_readonly("height", [](PySceneRenderer& r) { return r.renderer->height(); })
      .def_property_readonly("backend",
                             [](PySceneRenderer& r) { return r.renderer->backend_name(); })
      .def_property_readonly("device",
                             [](PySceneRenderer& r) { return r.renderer->compute_device_name(); })
      .def_property_readonly("render_device",
                             [](PySceneRenderer& r) { return r.renderer->render_device_name(); })
      .def_property_readonly(
          "shares_device", [](PySceneRenderer& r) { return r.renderer->shares_device(); },
          "True when the frames are drawn from the compute backend's own buffers (one Vulkan "
          "device), False when each frame copies them.");
  m.def(
      "save_png",
      [](const std::string& path, const py::array_t<uint8_t, py::array::c_style>& rgba) {
        if (rgba.ndim() != 3 || rgba.shape(2) != 4)
          bad_argument("masav.save_png", "rgba shape", py::repr(rgba.attr("shape")).cast<std::string>(),
                       "(height, width, 4)");
        Frame f{uint32_t(rgba.shape(1)), uint32_t(rgba.shape(0)),
                std::vector<uint8_t>(rgba.data(), rgba.data() + rgba.size())};
        py::gil_scoped_release nogil;
        save_png(path, f);
      },
      py::arg("path"), py::arg("rgba"),
      "Writes an (height, width, 4) uint8 RGBA array (a SceneRenderer frame) as a PNG.");
}

}  // namespace masav::python
