#include "engine/core/error.h"
#include "masav/scene.h"
#include "registry/check_catalog.h"
#include "registry/scene_catalog.h"

namespace masav {

scene::SceneFile load_scene(const std::string& path) {
  return scene::load_scene_file(path);
}

scene::SceneFile default_scene_of(std::string_view type) {
  return scene::default_scene(type);
}

void set_scene_value(scene::SceneFile& f, std::string_view assignment) {
  const size_t eq = assignment.find('=');
  if (eq == std::string_view::npos || eq == 0)
    throw_invalid("masav::set_scene_value", "assignment", assignment, "table.key=value");
  f.params.set_from_string(assignment.substr(0, eq), assignment.substr(eq + 1));
}

std::string scene_toml(const scene::SceneFile& f) {
  return scene::scene_to_toml(f.params, false);
}

std::vector<std::string> scene_kernels(const scene::SceneFile& f) {
  std::vector<std::string> names;
  for (KernelId k : scene::find_scene_type(f.type).kernels(f.params))
    names.emplace_back(kernel_name(k));
  return names;
}

verify::CrossCheckReport cross_check_scene(const scene::SceneFile& f, Backend& backend,
                                           Backend* reference) {
  if (reference) return verify::cross_check_scene(backend, *reference, f.params);
  const auto chosen = verify::open_reference(backend, f.params.get_text("verify.reference"));
  return verify::cross_check_scene(backend, *chosen, f.params);
}

}  // namespace masav
