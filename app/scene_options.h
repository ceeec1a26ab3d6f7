#pragma once
// Options shared by the scene commands (run, verify, export, demo): the scene file and
// `--set table.key=value` overrides, validated like the file itself.
#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "registry/scene_file.h"

namespace masav::app {

struct SceneChoice {
  std::string path;               // empty: the default scene type at its defaults
  std::vector<std::string> sets;  // "table.key=value"
};

void add_scene_options(CLI::App& cmd, SceneChoice& choice, bool path_required);
// Loads the file (or the defaults) and applies the overrides; errors name the key and range.
scene::SceneFile load_scene(const SceneChoice& choice);
// Creates `dir` if needed and proves it writable (a probe file, written then removed).
void ensure_writable_dir(const std::string& dir, const std::string& option);
// The ffmpeg executable on PATH, or "" when there is none.
std::string find_ffmpeg();

}  // namespace masav::app
