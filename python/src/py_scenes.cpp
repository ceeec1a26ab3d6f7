// Scene files from Python: loaded and checked as `masav run` and `masav verify` load them
// (registry/scene_file.h), overridden key by key as `--set table.key=value` does, written back
// as TOML, and cross-checked (masav.cross_check_scene takes a Scene or a path).
#include <fmt/format.h>
#include <pybind11/stl.h>

#include "engine/verify/cross_check.h"
#include "python/src/py_core.h"
#include "registry/check_catalog.h"
#include "registry/scene_catalog.h"
#include "registry/scene_file.h"

namespace masav::python {
namespace {

using scene::SceneFile;

// `set` as {"table.key": value}: each value as its text, checked as --set checks it.
void apply(SceneFile& f, const py::dict& set) {
  for (auto [k, v] : set) {
    std::string text;
    if (py::isinstance<py::bool_>(v))
      text = v.cast<bool>() ? "true" : "false";
    else
      text = py::str(v).cast<std::string>();
    f.params.set_from_string(py::str(k).cast<std::string>(), text);
  }
}

py::object value_of(const scene::ParamValue& v) {
  return std::visit([](const auto& x) { return py::cast(x); }, v);
}

std::vector<std::string> keys_of(const SceneFile& f) {
  std::vector<std::string> keys;
  for (const scene::TableSchema* t : f.params.tables())
    for (const scene::ParamSpec& p : t->params()) keys.push_back(t->name() + "." + p.key);
  return keys;
}

}  // namespace

void bind_scenes(py::module_& m) {
  py::class_<SceneFile>(m, "Scene",
                        "A scene file's parameters, every key checked against its scene type's "
                        "schema (masav schema prints them).")
      .def_readonly("source", &SceneFile::source)
      .def_readonly("type", &SceneFile::type)
      .def("keys", &keys_of, "Every parameter as table.key.")
      .def(
          "__getitem__",
          [](const SceneFile& f, const std::string& key) {
            if (!f.params.has(key))
              bad_argument(f.source, "key", key, "one of the scene's keys (Scene.keys())");
            return value_of(f.params.get(key));
          },
          py::arg("key"))
      .def(
          "set", [](SceneFile& f, const py::dict& values) { apply(f, values); }, py::arg("values"),
          "Overrides {\"table.key\": value}, checked as --set is.")
      .def_property_readonly(
          "toml", [](const SceneFile& f) { return scene::scene_to_toml(f.params, false); })
      .def("__repr__", [](const SceneFile& f) {
        return fmt::format("masav.Scene('{}', type '{}')", f.source, f.type);
      });

  m.def(
      "load_scene",
      [](const std::string& path, const py::dict& set) {
        SceneFile f = scene::load_scene_file(path);
        apply(f, set);
        return f;
      },
      py::arg("path"), py::arg("set") = py::dict(),
      "Reads a scene file (TOML) and applies `set` {\"table.key\": value} over it.");
  m.def(
      "parse_scene",
      [](const std::string& text, const py::dict& set) {
        SceneFile f = scene::parse_scene(text, "<text>");
        apply(f, set);
        return f;
      },
      py::arg("text"), py::arg("set") = py::dict(), "A scene from TOML text.");
  m.def(
      "default_scene", [](const std::string& type) { return scene::default_scene(type); },
      py::arg("type"), "A scene type (particles, atom, atom-volume, volume, sph) at its defaults.");
  m.def(
      "scene_types",
      [] {
        std::vector<std::pair<std::string, std::string>> out;
        for (const auto& t : scene::scene_types()) out.emplace_back(t.name, t.help);
        return out;
      },
      "The scene types: (name, help).");
  m.def(
      "scene_kernels",
      [](const SceneFile& f) {
        std::vector<std::string> out;
        for (KernelId k : scene::find_scene_type(f.type).kernels(f.params))
          out.emplace_back(kernel_name(k));
        return out;
      },
      py::arg("scene"), "The kernels the scene runs with its parameters.");
}

}  // namespace masav::python
