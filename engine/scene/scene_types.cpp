// The scene types built into masav. A new scene registers here with one line.
#include "engine/atom/atom_scene_types.h"
#include "engine/points/particles_scene.h"
#include "engine/scene/scene.h"
#include "engine/sph/sph_scene_type.h"

namespace masav::scene {

const std::vector<SceneType>& scene_types() {
  static const std::vector<SceneType> types = {
      points::particles_scene_type(),
      atom::atom_scene_type(),
      atom::atom_volume_scene_type(),
      sph::sph_scene_type(),
  };
  return types;
}

}  // namespace masav::scene
