// The cross-check from Python: the built-in check of each kernel (registry/check_catalog.cpp)
// on two backends, or every kernel a scene file uses, returning the report `masav verify`
// prints; and compare_outputs, the same checks' comparison (bit for bit, tolerances or
// chi-square) of outputs a Python caller computed on two backends.
#include <fmt/format.h>
#include <pybind11/stl.h>

#include <cstring>

#include "engine/verify/cross_check.h"
#include "python/src/py_arrays.h"
#include "registry/check_catalog.h"
#include "masav/cross_check.h"
#include "registry/kernel_check_inputs.h"
#include "registry/scene_catalog.h"
#include "registry/scene_file.h"

namespace masav::python {
namespace {

using verify::CheckOutputs;
using verify::CrossCheckReport;

KernelId kernel_of(const std::string& name) {
  const auto k = find_kernel(name);
  if (!k) bad_argument("masav.cross_check", "kernel", name, std::string(kernel_names_list()));
  return *k;
}

// Runs `work` with both backends' locks, without the GIL.
template <class Work>
auto with_both(PyBackend& a, PyBackend& b, Work&& work) {
  py::gil_scoped_release nogil;
  if (&a == &b) {
    std::lock_guard lock(a.mutex);
    return work();
  }
  std::scoped_lock lock(a.mutex, b.mutex);
  return work();
}

std::optional<KernelId> fault_of(const std::optional<std::string>& name) {
  if (!name) return std::nullopt;
  return kernel_of(*name);
}

CrossCheckReport check_kernels(const py::object& kernels, PyBackend& a, PyBackend& b,
                               std::optional<uint32_t> points, uint64_t seed,
                               const std::optional<std::string>& fault) {
  std::vector<std::string> names;
  if (py::isinstance<py::str>(kernels)) {
    const std::string s = kernels.cast<std::string>();
    if (s == "all")
      for (KernelId k : kAllKernels) names.emplace_back(kernel_name(k));
    else
      names.push_back(s);
  } else {
    names = kernels.cast<std::vector<std::string>>();
  }
  if (names.empty()) bad_argument("masav.cross_check", "kernels", "[]", "at least one kernel");
  // Refused here, so that the messages name Python's function.
  for (const std::string& name : names) kernel_of(name);
  if (points && *points == 0) bad_argument("masav.cross_check", "points", "0", "at least 1");
  CrossCheckOptions options;
  options.points = points;
  options.seed = seed;
  options.inject_fault = fault_of(fault);
  return with_both(a, b,
                   [&] { return masav::cross_check(names, *a.backend, *b.backend, options); });
}

CrossCheckReport check_scene(const py::object& scene, PyBackend& a,
                             const std::optional<std::reference_wrapper<PyBackend>>& ref,
                             const std::optional<std::string>& fault) {
  const scene::SceneFile f = py::isinstance<py::str>(scene)
                                 ? scene::load_scene_file(scene.cast<std::string>())
                                 : scene.cast<scene::SceneFile>();
  const std::optional<KernelId> k = fault_of(fault);
  if (ref)
    return with_both(a, ref->get(), [&] {
      return verify::cross_check_scene(*a.backend, *ref->get().backend, f.params, k);
    });
  return without_gil(a, [&](Backend& be) {
    // The scene's verify.reference (auto: the other GPU backend, else the CPU reference).
    auto reference = verify::open_reference(be, f.params.get_text("verify.reference"));
    return verify::cross_check_scene(be, *reference, f.params, k);
  });
}

// Outputs as a check compares them: integer arrays as words, float arrays as reals (real4
// arrays flattened row by row; a bool or other dtype is refused).
CheckOutputs outputs_of(const py::dict& d, const char* what) {
  CheckOutputs out;
  for (auto [k, v] : d) {
    verify::CheckOutput o;
    o.name = py::str(k).cast<std::string>();
    auto a = py::array::ensure(v);
    if (!a) bad_argument(what, o.name, py::repr(v).cast<std::string>(), "a numpy array");
    const std::string where = fmt::format("{} {}", what, o.name);
    const char kind = a.dtype().kind();
    if (kind == 'u' || kind == 'i') {
      auto w = py::array_t<uint32_t, py::array::c_style | py::array::forcecast>::ensure(a);
      o.words.assign(w.data(), w.data() + w.size());
    } else if (kind == 'f') {
      auto r = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(a);
      o.reals.assign(r.data(), r.data() + r.size());
    } else {
      bad_argument(where, "dtype", py::str(a.dtype()).cast<std::string>(),
                   "an integer or float array");
    }
    out.push_back(std::move(o));
  }
  return out;
}

py::dict row_dict(const verify::CheckRow& r) {
  py::dict d;
  d["kernel"] = r.kernel;
  d["kind"] = verify::check_kind_name(r.kind);
  d["passed"] = r.pass;
  d["metrics"] = r.metrics;
  d["tolerance"] = r.tolerance;
  d["numbers"] = r.numbers;
  d["error"] = r.error;
  d["not_compared"] = r.not_compared;
  d["refused_by"] = r.refused_by;
  d["advice"] = r.advice;
  return d;
}

}  // namespace

void bind_verify(py::module_& m) {
  py::class_<CrossCheckReport>(m, "CrossCheckReport",
                               "What `masav verify` prints: each kernel, both backends and "
                               "devices, the errors and the tolerances.")
      .def_property_readonly("passed", &CrossCheckReport::pass)
      .def_property_readonly("failures", &CrossCheckReport::failures)
      .def_property_readonly("not_compared", &CrossCheckReport::not_compared,
                             "Kernels a backend refused (e.g. a buffer over its limit): not "
                             "compared, counted apart from failures.")
      .def_readonly("scene", &CrossCheckReport::scene)
      .def_readonly("backend", &CrossCheckReport::backend)
      .def_readonly("device", &CrossCheckReport::device)
      .def_readonly("reference", &CrossCheckReport::reference)
      .def_readonly("reference_device", &CrossCheckReport::reference_device)
      .def_readonly("points", &CrossCheckReport::points)
      .def_readonly("seed", &CrossCheckReport::seed)
      .def_property_readonly("rows",
                             [](const CrossCheckReport& r) {
                               py::list l;
                               for (const auto& row : r.rows) l.append(row_dict(row));
                               return l;
                             })
      .def_property_readonly("text", &verify::format_report,
                             "The report as masav verify prints it.")
      .def_property_readonly("json", &verify::report_json, "The report as masav verify saves it.")
      .def("__str__", &verify::format_report)
      .def("__repr__", [](const CrossCheckReport& r) {
        return fmt::format("<CrossCheckReport {} vs {}: {} of {} kernels agree>", r.backend,
                           r.reference, r.rows.size() - r.failures() - r.not_compared(),
                           r.rows.size());
      });

  m.def("cross_check", &check_kernels, py::arg("kernels"), py::arg("backend"), py::arg("reference"),
        py::arg("points") = py::none(), py::arg("seed") = 1, py::arg("inject_fault") = py::none(),
        "Runs the built-in cross-check of `kernels` (a name, a list, or \"all\") on `backend` "
        "and `reference` with identical inputs (those `masav verify` sizes for the first scene "
        "that runs each kernel; `points` overrides their count). inject_fault: a kernel whose "
        "output `backend` perturbs, to see the check catch it.");
  m.def("cross_check_scene", &check_scene, py::arg("scene"), py::arg("backend"),
        py::arg("reference") = py::none(), py::arg("inject_fault") = py::none(),
        "`masav verify SCENE`: every kernel the scene (a masav.Scene or a file) uses, on `backend` "
        "and `reference` "
        "(default: the scene's verify.reference).");
  m.def(
      "check_inputs",
      [](const std::string& kernel, std::optional<uint32_t> points, uint64_t seed) {
        const verify::KernelCheckInputs ki =
            verify::kernel_check_inputs(kernel_of(kernel), points, seed, "masav.check_inputs");
        py::dict d;
        d["scene"] = ki.scene;
        d["points"] = ki.in.points;
        d["seed"] = ki.in.seed;
        d["grid"] = ki.in.grid ? py::cast(*ki.in.grid) : py::none();
        d["neighbor_radius"] = ki.in.neighbor_radius;
        return d;
      },
      py::arg("kernel"), py::arg("points") = py::none(), py::arg("seed") = 1,
      "The inputs cross_check and compare_outputs size a kernel's check with: its scene, point "
      "count, seed, grid and neighbour radius.");
  m.def(
      "compare_outputs",
      [](const std::string& kernel, const py::dict& got, const py::dict& want,
         std::optional<uint32_t> points, uint64_t seed) {
        const KernelId k = kernel_of(kernel);
        const verify::KernelCheck* check = verify::find_kernel_check(k);
        if (!check)
          throw Error("", kernel, "no cross-check is registered for this kernel",
                      "add one in registry/check_catalog.cpp");
        const verify::KernelCheckInputs ki =
            verify::kernel_check_inputs(k, points, seed, "masav.compare_outputs");
        const verify::Verdict v =
            check->compare(outputs_of(got, "got"), outputs_of(want, "want"), ki.in);
        py::dict d;
        d["kernel"] = kernel;
        d["kind"] = verify::check_kind_name(check->kind);
        d["passed"] = v.pass;
        d["metrics"] = v.metrics;
        d["tolerance"] = v.tolerance;
        d["numbers"] = v.numbers;
        return d;
      },
      py::arg("kernel"), py::arg("got"), py::arg("want"), py::arg("points") = py::none(),
      py::arg("seed") = 1,
      "Compares outputs {name: array} of `kernel` from two backends as its built-in "
      "cross-check does (bit for bit, its tolerances, or its chi-square), with the names the "
      "check gives its outputs; returns passed, metrics and the tolerance allowed.");
}

}  // namespace masav::python
