// masav.Atom: the electron-cloud pipeline of `masav atom` (engine/atom/atom_scene.h) -- cloud,
// density grid, scattering table, illumination, view, voxelize -- each stage callable alone,
// its arrays as numpy copies, and the voxelized volume raymarched to an (H, W, 4) image.
// orbital_tables gives orbital_sample's inputs for the kernel itself.
#include <fmt/format.h>
#include <pybind11/stl.h>

#include <cmath>
#include <cstring>
#include <optional>

#include "engine/atom/atom_scene.h"
#include "engine/atom/atom_schema.h"
#include "engine/atom/orbital.h"
#include "engine/atom/orbital_tables.h"
#include "engine/atom/scatter_cache.h"
#include "engine/volume/transfer_function.h"
#include "python/src/py_arrays.h"
#include "python/src/py_casters.h"

namespace masav::python {
namespace {

struct PyAtom {
  BackendRef backend;
  std::unique_ptr<atom::AtomScene> scene;
  atom::ViewPreset view = atom::ViewPreset::front;
};

// A state by preset name ("state1" .. "state10") or as (n, l, m).
atom::OrbitalState state_of(const py::object& s, bool real) {
  atom::OrbitalState st;
  if (py::isinstance<py::str>(s)) {
    st = atom::preset_state(s.cast<std::string>());
  } else {
    const auto t = s.cast<std::tuple<int, int, int>>();
    st = {std::get<0>(t), std::get<1>(t), std::get<2>(t), false};
  }
  st.real = real;
  atom::validate_state(st, "masav.Atom");
  return st;
}

OrbitalPlacement placement_of(const std::string& p) {
  if (p == "exact") return OrbitalPlacement::exact;
  if (p == "shells") return OrbitalPlacement::shells;
  bad_argument("masav.Atom", "placement", p, "exact or shells");
}

std::unique_ptr<PyAtom> create(BackendRef b, const py::object& state, bool real, uint32_t particles,
                               uint64_t seed, const std::string& placement, uint32_t density_dims,
                               uint32_t volume_dims, uint32_t photons, float power, float tau_peak,
                               float s, float t, const std::string& view, bool use_cache,
                               const std::optional<std::string>& cache_dir) {
  atom::AtomSceneOptions o;
  o.state = state_of(state, real);
  o.placement = placement_of(placement);
  o.particles = particles;
  o.seed = seed;
  o.density_dims = density_dims;
  o.volume_dims = volume_dims;
  o.scatter.photons_per_row = photons;
  atom::check_scatter_cost(o.scatter, "photons");
  o.source_power_lm = power;
  o.tau_peak = tau_peak;
  o.s = s;
  o.t = t;
  o.use_cache = use_cache;
  o.cache_dir = cache_dir.value_or("");
  auto a = std::make_unique<PyAtom>();
  a->view = atom::parse_view(view);
  // The viewer of the lighting sits where the raymarch camera does (as `masav atom` puts it).
  const float half = float(atom::box_half_width(o.state, o.box_probability));
  o.viewer = atom::view_eye(a->view, 1.9f * half * std::sqrt(3.0f));
  a->backend = std::move(b);
  a->scene = without_gil(*a->backend,
                         [&](Backend& be) { return std::make_unique<atom::AtomScene>(be, o); });
  return a;
}

template <class Stage>
void run_stage(PyAtom& a, Stage stage) {
  without_gil(*a.backend, [&](Backend&) { stage(*a.scene); });
}

// A stage's output as a numpy copy; an error naming the stage that makes it when it has not run.
template <class T>
py::array output(PyAtom& a, const Buffer<T>& b, const char* name, const char* stage) {
  if (!b.valid())
    throw Error(a.backend->backend->name(), "masav.Atom",
                fmt::format("{} is not computed yet", name),
                fmt::format("run {}() (or run()) first", stage));
  PyBuffer view(a.backend, elem_kind_of<T>(), const_cast<Buffer<T>*>(&b), py::none());
  return download_array(*a.backend, view);
}

py::array raymarch(PyAtom& a, uint32_t width, uint32_t height,
                   const std::optional<py::array>& transfer) {
  if (!a.scene->sample.valid())
    throw Error(a.backend->backend->name(), "masav.Atom", "the volume is not voxelized yet",
                "run voxelize() (or run()) first");
  std::vector<Vec4d> tf = volume::resample_transfer(volume::default_transfer_points());
  if (transfer) {
    const size_t n =
        checked_elements(*transfer, ElemKind::real4, "Atom.raymarch transfer", true, false);
    auto d = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(*transfer);
    tf.resize(n);
    std::memcpy(static_cast<void*>(tf.data()), d.data(), n * sizeof(Vec4d));
  }
  if (width < 1 || width > 16384 || height < 1 || height > 16384)
    bad_argument("Atom.raymarch", "width x height", fmt::format("{}x{}", width, height),
                 "from 1 to 16384 pixels each");
  const std::vector<Vec4d> img = without_gil(*a.backend, [&](Backend& be) {
    const RaymarchParams rp = atom::default_raymarch(a.scene->volume(), a.view, width, height);
    return atom::render_volume(be, a.scene->volume(), a.scene->sample, tf, rp);
  });
  py::array_t<double> out({py::ssize_t(height), py::ssize_t(width), py::ssize_t(4)});
  std::memcpy(out.mutable_data(), img.data(), img.size() * sizeof(Vec4d));
  return out;
}

}  // namespace

void bind_atom(py::module_& m) {
  m.def(
      "orbital_tables",
      [](const py::object& state, bool real, const std::string& placement, uint32_t count,
         uint64_t seed) {
        const auto t =
            atom::make_orbital_tables(state_of(state, real), placement_of(placement), count, seed);
        return py::make_tuple(t.params,
                              py::array_t<uint32_t>(py::ssize_t(t.cdf.size()), t.cdf.data()));
      },
      py::arg("state"), py::arg("real") = false, py::arg("placement") = "exact",
      py::arg("count") = 100000, py::arg("seed") = 1,
      "orbital_sample's inputs for a state (\"state1\".. or (n, l, m)): (OrbitalSampleParams, "
      "the uint32 tables).");

  py::class_<PyAtom>(m, "Atom",
                     "The hydrogen electron cloud of `masav atom`: sampled, lit through its "
                     "scattering table, voxelized and raymarched.")
      .def(py::init(&create), py::arg("backend"), py::arg("state") = "state1",
           py::arg("real") = false, py::arg("particles") = 200000, py::arg("seed") = 1,
           py::arg("placement") = "exact", py::arg("density_dims") = 60,
           py::arg("volume_dims") = 60, py::arg("photons") = 4096, py::arg("power") = 250000.0f,
           py::arg("tau_peak") = 0.5f, py::arg("s") = 0.6f, py::arg("t") = 0.4f,
           py::arg("view") = "front", py::arg("use_cache") = true,
           py::arg("cache_dir") = py::none(),
           "state: \"state1\"..\"state10\" or (n, l, m); the options of `masav atom`. "
           "cache_dir: the scattering table's cache directory (None: no cache, the table is "
           "computed every time; the module never reads MASAV_CACHE_DIR).")
      .def("build_cloud", [](PyAtom& a) { run_stage(a, [](auto& s) { s.build_cloud(); }); })
      .def("build_density", [](PyAtom& a) { run_stage(a, [](auto& s) { s.build_density(); }); })
      .def("build_table", [](PyAtom& a) { run_stage(a, [](auto& s) { s.build_table(); }); })
      .def("illuminate", [](PyAtom& a) { run_stage(a, [](auto& s) { s.illuminate(); }); })
      .def("view_light", [](PyAtom& a) { run_stage(a, [](auto& s) { s.view(); }); })
      .def("voxelize", [](PyAtom& a) { run_stage(a, [](auto& s) { s.voxelize(); }); })
      .def(
          "run", [](PyAtom& a) { run_stage(a, [](auto& s) { s.run_all(); }); },
          "Every stage in order: cloud, density, table, illuminate, view_light, voxelize.")
      .def("raymarch", &raymarch, py::arg("width") = 256, py::arg("height") = 256,
           py::arg("transfer") = py::none(),
           "The voxelized volume raymarched from the scene's view: (height, width, 4) RGBA.")
      .def_property_readonly(
          "positions",
          [](PyAtom& a) { return output(a, a.scene->positions, "positions", "build_cloud"); })
      .def_property_readonly(
          "density",
          [](PyAtom& a) { return output(a, a.scene->density, "density", "build_density"); })
      .def_property_readonly(
          "phase", [](PyAtom& a) { return output(a, a.scene->phase, "phase", "build_table"); })
      .def_property_readonly(
          "illumination",
          [](PyAtom& a) { return output(a, a.scene->illumination, "illumination", "illuminate"); })
      .def_property_readonly(
          "light", [](PyAtom& a) { return output(a, a.scene->light, "light", "view_light"); })
      .def_property_readonly(
          "volume",
          [](PyAtom& a) {
            py::array v = output(a, a.scene->sample, "volume", "voxelize");
            const auto d = a.scene->volume().dims;
            return v.reshape({py::ssize_t(d.z), py::ssize_t(d.y), py::ssize_t(d.x)});
          },
          "The voxelized sample (Z, Y, X) in [0, 1], what raymarch() draws.")
      .def_property_readonly("light_params", [](PyAtom& a) { return a.scene->light_params(); })
      .def_property_readonly("density_grid", [](PyAtom& a) { return a.scene->density_grid(); })
      .def_property_readonly("volume_grid", [](PyAtom& a) { return a.scene->volume_grid(); })
      .def_property_readonly("volume_desc", [](PyAtom& a) { return a.scene->volume(); })
      .def_property_readonly("exposure", [](PyAtom& a) {
        return without_gil(*a.backend, [&](Backend&) { return a.scene->exposure(); });
      });
}

}  // namespace masav::python
