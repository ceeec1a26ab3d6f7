#pragma once
// Scene files in TOML (toml++). Every table and key is checked against the scene type's schema:
// an unknown table or key, a value of the wrong type or out of range is an error naming the
// file and line, the key, the value and what is allowed. Keys left out take their defaults.
#include <string>
#include <string_view>

#include "engine/scene/param_schema.h"

namespace masav::scene {

struct SceneFile {
  std::string source;  // the path, or "<text>"
  std::string type;    // [scene] type
  ParamSet params;     // every parameter of the type's tables
};

SceneFile load_scene_file(const std::string& path);
SceneFile parse_scene(std::string_view toml_text, std::string_view source);
// A scene type at its defaults (what `masav run` uses without a file).
SceneFile default_scene(std::string_view type);
// The scene as TOML with every parameter, its help and allowed range as comments: the
// reference of the file format (`masav schema`), and what `masav export` writes as the
// resolved scene.
std::string scene_to_toml(const ParamSet& params, bool with_help);

}  // namespace masav::scene
