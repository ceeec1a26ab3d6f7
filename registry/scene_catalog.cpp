// The scene types built into masav. A new scene registers here with one line.
#include "registry/scene_catalog.h"

#include "engine/atom/atom_scene_types.h"
#include "engine/core/error.h"
#include "engine/points/particles_scene.h"
#include "engine/sph/sph_scene_type.h"
#include "engine/volume/volume_scene.h"
#include "registry/common_tables.h"

namespace masav::scene {

const std::vector<SceneType>& scene_types() {
  // clang-format off
  static const std::vector<SceneType> types = {
      points::particles_scene_type(),
      atom::atom_scene_type(),
      atom::atom_volume_scene_type(),
      volume::volume_scene_type(),
      sph::sph_scene_type(),
  };
  // clang-format on
  return types;
}

std::vector<std::string> scene_type_names() {
  std::vector<std::string> names;
  for (const auto& t : scene_types()) names.push_back(t.name);
  return names;
}

const SceneType& find_scene_type(std::string_view name) {
  for (const auto& t : scene_types())
    if (t.name == name) return t;
  std::string all;
  for (const auto& n : scene_type_names()) all += (all.empty() ? "" : ", ") + n;
  throw_invalid("scene", "scene.type", std::string(name), "one of " + all);
}

ParamSet default_params(const SceneType& type) {
  ParamSet p;
  for (const TableSchema* t : common_tables()) p.add_table(*t);
  for (const TableSchema* t : type.tables) p.add_table(*t);
  p.set("scene.type", type.name);
  return p;
}

}  // namespace masav::scene
