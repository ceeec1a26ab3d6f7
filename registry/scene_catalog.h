#pragma once
// The scene types built into this binary (scene_catalog.cpp lists them), by name, and their
// parameters at the defaults.
#include <string>
#include <string_view>
#include <vector>

#include "engine/scene/scene.h"

namespace masav::scene {

const std::vector<SceneType>& scene_types();
std::vector<std::string> scene_type_names();
// Throws masav::Error naming scene.type and the types there are.
const SceneType& find_scene_type(std::string_view name);
// Every table of a scene type (common + domain) at its defaults.
ParamSet default_params(const SceneType& type);

}  // namespace masav::scene
