#pragma once
/// \file
/// Scene files (TOML): loaded and checked against their scene type's schema as `masav run` and
/// `masav verify` load them, overridden key by key as `--set table.key=value` does, written back
/// as TOML, and cross-checked kernel by kernel.
#include <string>
#include <string_view>
#include <vector>

#include "engine/kernels/backend.h"
#include "engine/verify/cross_check.h"
#include "registry/scene_file.h"

namespace masav {

/// Reads and checks a scene file. Throws masav::Error naming the file, line and key.
scene::SceneFile load_scene(const std::string& path);

/// A scene type (particles, atom, atom-volume, volume, sph) at its defaults.
scene::SceneFile default_scene_of(std::string_view type);

/// Applies one `table.key=value` override, checked as `--set` checks it.
void set_scene_value(scene::SceneFile& scene, std::string_view assignment);

/// The scene as TOML, every parameter written (what `masav export` writes as scene.toml).
std::string scene_toml(const scene::SceneFile& scene);

/// The kernels the scene runs with its parameters.
std::vector<std::string> scene_kernels(const scene::SceneFile& scene);

/// Every kernel the scene runs, on `backend` against `reference` (null: the scene's
/// verify.reference, as `masav verify` picks it).
verify::CrossCheckReport cross_check_scene(const scene::SceneFile& scene, Backend& backend,
                                           Backend* reference = nullptr);

}  // namespace masav
