// The kernels' parameter structs as Python classes: one line per struct names its fields (C++
// gives no field names to iterate), and every class gets the same constructor from keywords, the
// same errors and the same repr. Enum fields take the enum or its name as a string:
//   masav.RadixSortParams(n=1000, key_bits=20, impl="portable")
// Vectors are tuples, 64-bit words ints (py_casters.h). The helpers that fill grid parameters
// as the engine does (make_grid_params, ...) are here too.
#include <fmt/format.h>
#include <pybind11/stl.h>

#include "engine/core/pp.h"
#include "python/src/py_casters.h"
#include "python/src/py_core.h"

namespace masav::python {
namespace {

std::string join(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& x : v) s += (s.empty() ? "" : ", ") + x;
  return s;
}

// Sets `name` of the Python object `o` to `value`, with masav's error for a bad name or value.
void set_field(const char* type, py::object& o, const std::vector<std::string>& fields,
               const std::string& name, py::handle value) {
  if (std::find(fields.begin(), fields.end(), name) == fields.end())
    bad_argument(type, "field", name, "one of " + join(fields));
  py::object current = o.attr(name.c_str());
  py::object type_of = py::type::of(current);
  py::object v = py::reinterpret_borrow<py::object>(value);
  // An enum by its name.
  if (py::isinstance<py::str>(v) && py::hasattr(type_of, "__members__")) {
    py::dict members = type_of.attr("__members__");
    const std::string s = v.cast<std::string>();
    if (!members.contains(s)) {
      std::vector<std::string> names;
      for (auto [k, _] : members) names.push_back(py::str(k).cast<std::string>());
      bad_argument(type, name, s, "one of " + join(names));
    }
    v = members[py::str(s)];
  }
  try {
    o.attr(name.c_str()) = v;
  } catch (py::error_already_set& e) {
    if (!e.matches(PyExc_TypeError)) throw;
    bad_argument(type, name, py::repr(v).cast<std::string>(),
                 fmt::format("a {}", py::str(type_of.attr("__name__")).cast<std::string>()));
  }
}

template <class T>
py::class_<T> params_class(py::module_& m, const char* name, const char* doc,
                           std::vector<std::string> fields) {
  py::class_<T> c(m, name, doc);
  c.def(py::init([name, fields](py::kwargs kw) {
          T t{};
          py::object o = py::cast(&t, py::return_value_policy::reference);
          for (auto [k, v] : kw) set_field(name, o, fields, py::str(k).cast<std::string>(), v);
          return t;
        }),
        "Every field defaults as in C++; give any of them by name.");
  c.def("__repr__", [name, fields](py::object self) {
    std::string s;
    for (const auto& f : fields)
      s += fmt::format("{}{}={}", s.empty() ? "" : ", ", f,
                       py::repr(self.attr(f.c_str())).cast<std::string>());
    return fmt::format("{}({})", name, s);
  });
  c.def_property_readonly_static("fields", [fields](py::object) { return fields; });
  c.def("__copy__", [](const T& t) { return T(t); });
  return c;
}

}  // namespace

// MASAV_PY_PARAMS(module, Type, doc, (field)...): the class of Type with those fields.
#define MASAV_PY_FIELD_NAME(d, field) #field,
#define MASAV_PY_FIELD(Type, field) .def_readwrite(#field, &Type::field)
#define MASAV_PY_PARAMS(m, Type, doc, ...)                                                \
  params_class<Type>(m, #Type, doc, {MASAV_PP_EACH(MASAV_PY_FIELD_NAME, _, __VA_ARGS__)}) \
      MASAV_PP_EACH(MASAV_PY_FIELD, Type, __VA_ARGS__)

using Clip = RaymarchParams::Clip;
using Shading = RaymarchParams::Shading;

void bind_params(py::module_& m) {
  py::enum_<SortImpl>(m, "SortImpl")
      .value("portable", SortImpl::portable)
      .value("vendor", SortImpl::vendor);
  py::enum_<SphPressureModel>(m, "SphPressureModel")
      .value("wcsph", SphPressureModel::wcsph)
      .value("thesis", SphPressureModel::thesis)
      .value("dfsph", SphPressureModel::dfsph);
  py::enum_<SphStageOp>(m, "SphStageOp")
      .value("euler", SphStageOp::euler)
      .value("symplectic_euler", SphStageOp::symplectic_euler)
      .value("rk4_stage1", SphStageOp::rk4_stage1)
      .value("rk4_stage2", SphStageOp::rk4_stage2)
      .value("rk4_stage3", SphStageOp::rk4_stage3)
      .value("rk4_final", SphStageOp::rk4_final)
      .value("kick_drift", SphStageOp::kick_drift)
      .value("kick", SphStageOp::kick)
      .value("accelerate", SphStageOp::accelerate)
      .value("drift", SphStageOp::drift);
  py::enum_<SphReach>(m, "SphReach")
      .value("none", SphReach::none)
      .value("record", SphReach::record)
      .value("walk", SphReach::walk);
  py::enum_<DfsphSolve>(m, "DfsphSolve")
      .value("divergence", DfsphSolve::divergence)
      .value("density", DfsphSolve::density);
  py::enum_<OrbitalPlacement>(m, "OrbitalPlacement")
      .value("exact", OrbitalPlacement::exact)
      .value("shells", OrbitalPlacement::shells);
  py::enum_<ScatterStart>(m, "ScatterStart")
      .value("surface", ScatterStart::surface)
      .value("centre", ScatterStart::centre);
  py::enum_<OpticalPath>(m, "OpticalPath")
      .value("exact", OpticalPath::exact)
      .value("midpoint", OpticalPath::midpoint);
  py::enum_<Compositing>(m, "Compositing")
      .value("front_to_back", Compositing::front_to_back)
      .value("lerp", Compositing::lerp);

  MASAV_PY_PARAMS(m, DriftParams, "drift_points", (box_lo), (speed), (box_extent), (time_s), (n));
  MASAV_PY_PARAMS(m, PhiloxParams, "philox_u32, philox_uniform: a Philox4x32-10 stream", (seed),
                  (stream), (first_block));
  MASAV_PY_PARAMS(m, RadixSortParams, "radix_sort: stable LSD sort on the low key_bits", (n),
                  (key_bits), (impl));
  MASAV_PY_PARAMS(m, GridParams, "the hash grid (make_grid_params fills inv_cell)", (origin),
                  (cell_size), (dims), (n), (inv_cell));
  MASAV_PY_PARAMS(m, GatherParams, "gather: dst[i] = src[order[i]]", (n));
  MASAV_PY_PARAMS(m, NeighborParams, "grid_count_neighbors (make_neighbor_params)", (grid),
                  (radius), (radius2), (max_candidates));
  MASAV_PY_PARAMS(m, CellCountParams, "grid_count_cells", (n), (cell_count));
  MASAV_PY_PARAMS(m, CellAssignCountParams, "grid_assign_count", (grid));
  MASAV_PY_PARAMS(m, CellOffsetParams, "grid_cell_offsets", (cell_count));
  MASAV_PY_PARAMS(m, CellScatterParams, "grid_scatter_cells", (n), (cell_count));
  MASAV_PY_PARAMS(m, CellRankParams, "grid_rank_in_cell, grid_rank_and_move", (n), (cell_count),
                  (max_per_cell));
  MASAV_PY_PARAMS(m, SphStepParams, "sph_density, sph_forces (SI units)", (grid), (n), (first),
                  (count), (max_candidates), (model), (h), (reach), (reach_radius), (mass),
                  (rest_density), (sound_speed), (clamp_negative_pressure), (gradient_correction),
                  (kp), (viscosity), (gravity), (walls), (box_min), (box_max));
  MASAV_PY_PARAMS(m, SphIntegrateParams, "sph_integrate: one integrator stage, then the walls", (n),
                  (first), (count), (op), (dt), (walls), (box_min), (box_max), (restitution),
                  (tangential_damping));
  MASAV_PY_PARAMS(m, DfsphParams, "dfsph_factor, dfsph_rate, dfsph_correct", (step), (solve), (dt),
                  (slot), (first), (warm_scale), (min_neighbors), (stop_slot), (stop_units));
  MASAV_PY_PARAMS(m, OrbitalSampleParams, "orbital_sample", (count), (placement), (seed),
                  (radial_bins), (polar_bins), (azimuth_bins), (azimuth_periods), (radial_max_a0),
                  (azimuth_offset));
  MASAV_PY_PARAMS(m, CloudDensityParams, "cloud_density", (grid), (particles));
  MASAV_PY_PARAMS(m, ScatterTableParams, "scatter_table: Monte Carlo multiple scattering", (rows),
                  (first_row), (bins), (photons_per_row), (seed), (max_scatterings), (start),
                  (direction), (tau_step), (g), (albedo), (weight_threshold));
  MASAV_PY_PARAMS(m, NebulaLightParams, "nebula_illuminate, nebula_view", (grid), (nucleus),
                  (source_power_lm), (viewer), (kappa_a2), (albedo), (core_radius_a0), (step_a0),
                  (path), (table_rows), (table_bins), (table_tau_step));
  MASAV_PY_PARAMS(m, VoxelizeParams, "voxelize", (grid), (s), (t), (light_to_unit));
  MASAV_PY_PARAMS(m, VolumeDesc, "a scalar volume: dims, box and value range", (dims), (value_min),
                  (box_min), (value_max), (box_max));
  MASAV_PY_PARAMS(m, VolumeBrickParams, "volume_bricks", (volume), (brick), (tf_size));
  MASAV_PY_PARAMS(m, BrickSkipParams, "volume_brick_skip", (bricks), (axis), (radius));
  MASAV_PY_PARAMS(m, Clip, "raymarch: an axis-aligned clipping plane", (enabled), (axis),
                  (position), (keep_above));
  MASAV_PY_PARAMS(m, Shading, "raymarch: Blinn-Phong shading from the gradient", (enabled),
                  (headlight), (light_dir), (ambient), (diffuse), (specular), (shininess));
  MASAV_PY_PARAMS(m, RaymarchParams, "raymarch: the camera, the image and the ray knobs", (volume),
                  (width), (height), (eye), (target), (up), (fov_y_deg), (step), (reference_step),
                  (termination_alpha), (skip_empty), (preintegrate), (brick), (tf_size), (mode),
                  (clip), (shading));

  m.def("make_grid_params", &make_grid_params, py::arg("origin"), py::arg("cell_size"),
        py::arg("dims"), py::arg("n"),
        "A grid over dims cells of cell_size from origin, n points.");
  m.def("make_neighbor_params", &make_neighbor_params, py::arg("grid"), py::arg("radius"));
  m.def("grid_cell_count", &grid_cell_count, py::arg("grid"));
  m.def("grid_key_bits", &grid_key_bits, py::arg("grid"),
        "The key bits radix_sort needs for the grid's largest cell id.");
  m.def("make_volume_desc", &make_volume_desc, py::arg("dims"), py::arg("box_min"),
        py::arg("box_max"), py::arg("value_min") = 0.0f, py::arg("value_max") = 1.0f);

  // The sizes the kernels' small buffers take (engine/kernels/*_params.h).
  py::dict c;
  c["SPH_STAT_WORDS"] = kSphStatWords;
  c["SPH_ROW_MASK_WORDS"] = kSphRowMaskWords;
  c["SPH_STATE_STRIDE"] = kSphStateStride;
  c["SPH_ALL_PARTICLES"] = kSphAllParticles;
  c["DFSPH_RESIDUAL_WORDS"] = kDfsphResidualWords;
  c["DFSPH_MAX_SLOTS"] = kDfsphMaxSlots;
  c["DFSPH_NO_STOP"] = kDfsphNoStop;
  c["SCATTER_EXTRAS"] = kScatterExtras;
  c["PREINTEGRATED_PER_ENTRY"] = kPreintegratedPerEntry;
  c["CDF_ONE"] = kCdfOne;
  c["ORBITAL_STREAM"] = kOrbitalStream;
  m.attr("constants") = c;
}

}  // namespace masav::python
