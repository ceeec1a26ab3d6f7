// masav.backends() and masav.Backend: the backends built into the module, each with its devices
// or why it is absent, and construction by name (registry/backends.h), with a device choice and
// the typed tuning options of `--tune key=value`.
#include <fmt/format.h>
#include <pybind11/stl.h>

#include <optional>

#include "engine/core/tuning.h"
#include "python/src/py_arrays.h"
#include "registry/backends.h"

namespace masav::python {
namespace {

std::string device_repr(const DeviceStatus& d) {
  return fmt::format("{}: {} ({}{})", d.index, d.name, d.type,
                     d.usable ? "" : ", unusable: " + d.reason);
}

std::string status_repr(const BackendStatus& s) {
  if (!s.available) return fmt::format("<{}: absent: {}>", s.name, s.reason);
  std::string devices;
  for (const auto& d : s.devices) devices += (devices.empty() ? "" : "; ") + device_repr(d);
  return fmt::format("<{}: available: {}>", s.name, devices);
}

BackendRef open(const std::string& name, const std::string& device, const py::object& tune,
                bool count_loop_ticks, const std::optional<std::string>& cache_dir, bool validation,
                const std::optional<std::string>& loader) {
  BackendRequest request;
  request.tuning = tuning_of(tune);
  request.count_loop_ticks = count_loop_ticks;
  request.cache_dir = cache_dir.value_or("");
  VulkanSettings vulkan;
  vulkan.validation = validation;
  if (loader) vulkan.loader = *loader;
  auto ref = std::make_shared<PyBackend>();
  ref->requested = name;
  {
    py::gil_scoped_release nogil;  // a device's start takes a while (lavapipe compiles)
    ref->backend = create_backend(name, device, request, vulkan);
  }
  return ref;
}

py::dict capabilities(const Capabilities& c) {
  py::dict d;
  d["backend"] = c.backend;
  d["device_name"] = c.device_name;
  d["vendor"] = c.vendor;
  d["device_type"] = c.device_type;
  d["driver"] = c.driver;
  d["subgroup_size"] = c.subgroup_size;
  d["max_workgroup_size"] = c.max_workgroup_size;
  d["max_buffer_bytes"] = c.max_buffer_bytes;
  d["device_memory_bytes"] = c.device_memory_bytes;
  d["real_is_double"] = c.real_is_double;
  d["threads"] = c.threads;
  d["max_loop_iterations"] = c.max_loop_iterations;
  return d;
}

py::dict counters(const DeviceCounters& c) {
  py::dict d;
  d["launches"] = c.launches;
  d["barriers"] = c.barriers;
  d["host_syncs"] = c.host_syncs;
  d["fills"] = c.fills;
  d["device_copies"] = c.device_copies;
  d["bytes_to_device"] = c.bytes_to_device;
  d["bytes_to_host"] = c.bytes_to_host;
  d["pipelines_built"] = c.pipelines_built;
  return d;
}

}  // namespace

Tuning tuning_of(const py::object& tune, std::string_view where) {
  Tuning t;
  if (tune.is_none()) return t;
  if (py::isinstance<py::dict>(tune)) {
    for (auto [k, v] : tune.cast<py::dict>())
      set_tuning(t, py::str(k).cast<std::string>() + "=" + py::str(v).cast<std::string>());
    return t;
  }
  if (py::isinstance<py::str>(tune))
    bad_argument(where, "tune", tune.cast<std::string>(),
                 "a dict {\"key\": value} or a list of \"key=value\" strings");
  for (auto a : tune) set_tuning(t, py::str(a).cast<std::string>());
  return t;
}

BackendClass bind_backends(py::module_& m) {
  py::class_<DeviceStatus>(m, "DeviceStatus", "One device of a backend, as `masav info` lists it.")
      .def_readonly("index", &DeviceStatus::index)
      .def_readonly("name", &DeviceStatus::name)
      .def_readonly("type", &DeviceStatus::type)
      .def_readonly("detail", &DeviceStatus::detail)
      .def_readonly("usable", &DeviceStatus::usable)
      .def_readonly("reason", &DeviceStatus::reason)
      .def("__repr__", &device_repr);
  py::class_<BackendStatus>(m, "BackendStatus",
                            "A backend of this build: available with its devices, or why not.")
      .def_readonly("name", &BackendStatus::name)
      .def_readonly("built", &BackendStatus::built)
      .def_readonly("available", &BackendStatus::available)
      .def_readonly("reason", &BackendStatus::reason)
      .def_readonly("devices", &BackendStatus::devices)
      .def("__repr__", &status_repr);
  m.def(
      "backends",
      [] {
        py::gil_scoped_release nogil;  // probing the Vulkan and CUDA drivers takes a moment
        return list_backends();
      },
      "Every backend masav knows (vulkan, cuda, cpu): available with its devices, or the reason "
      "it is absent.");
  m.def("auto_backend", &auto_backend_name, "The backend `auto` picks now: cuda, vulkan or cpu.");
  m.def(
      "tuning_keys",
      [] {
        std::vector<std::tuple<std::string, std::string, std::string>> out;
        for (const TuningKey& k : tuning_keys())
          out.emplace_back(std::string(k.key), std::string(k.values), std::string(k.description));
        return out;
      },
      "The tuning options Backend(tune=...) takes: (key, values, what it chooses).");

  BackendClass cls(m, "Backend",
                   "A compute backend: the CPU reference, Vulkan or CUDA. Its methods run the "
                   "kernels of masav's kernel list on numpy arrays or masav.Buffer objects.");
  cls.def(py::init(&open), py::arg("name") = "auto", py::arg("device") = "",
          py::arg("tune") = py::none(), py::arg("count_loop_ticks") = false,
          py::arg("cache_dir") = py::none(), py::arg("validation") = false,
          py::arg("loader") = py::none(),
          "name: cpu, vulkan, cuda or auto (CUDA if it has a device, else Vulkan, else the CPU "
          "reference). device: an index or part of a name (\"\": the best). tune: the tuning "
          "options as {\"key\": value} or [\"key=value\"] (masav.tuning_keys()). cache_dir: "
          "the Vulkan pipeline cache's directory (None: no cache). validation: Vulkan's "
          "validation layer. loader: the Vulkan loader library (None: libvulkan.so.1). The "
          "module never reads the environment (MASAV_CACHE_DIR and the like are the CLI's).")
      .def_property_readonly("name", [](PyBackend& b) { return b.backend->name(); })
      .def_property_readonly("requested", [](PyBackend& b) { return b.requested; })
      .def_property_readonly("device", [](PyBackend& b) { return b.backend->caps().device_name; })
      .def_property_readonly(
          "real_dtype",
          [](PyBackend& b) { return dtype_of(ElemKind::real, b.backend->real_bytes()); },
          "The dtype of real and real4 buffers: float64 on the CPU reference, float32 on GPUs.")
      .def_property_readonly("capabilities",
                             [](PyBackend& b) { return capabilities(b.backend->caps()); })
      .def_property_readonly(
          "tuning", [](PyBackend& b) { return describe(b.backend->tuning()); },
          "The options that are not automatic, as key=value words.")
      .def_property_readonly("counters",
                             [](PyBackend& b) { return counters(b.backend->counters()); })
      .def(
          "finish", [](PyBackend& b) { without_gil(b, [](Backend& be) { be.finish(); }); },
          "Waits for the work recorded so far (downloads wait by themselves).")
      .def("__repr__", [](PyBackend& b) {
        return fmt::format("masav.Backend('{}', device='{}')", b.backend->name(),
                           b.backend->caps().device_name);
      });
  return cls;
}

}  // namespace masav::python
