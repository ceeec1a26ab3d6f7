#pragma once
// The scene types `atom` (the lit cloud as point sprites coloured by their light) and
// `atom-volume` (the cloud voxelized and raymarched, optionally with the particles over it).
#include "engine/scene/scene.h"

namespace masav::atom {

scene::SceneType atom_scene_type();
scene::SceneType atom_volume_scene_type();

}  // namespace masav::atom
