#pragma once
// Options shared by the scene commands (run, verify, export, demo): the scene file and
// `--set table.key=value` overrides, validated like the file itself.
#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "app/commands.h"
#include "engine/io/writable_paths.h"
#include "registry/scene_file.h"

namespace masav::app {

struct SceneChoice {
  std::string path;               // empty: the default scene type at its defaults
  std::vector<std::string> sets;  // "table.key=value"
};

void add_scene_options(CLI::App& cmd, SceneChoice& choice, bool path_required);
// A scene command (add_command): the optional scene file and --set first, then --backend and
// --device; `Options` has a SceneChoice `scene` and a BackendChoice `choice`.
template <class Options>
CLI::App* add_scene_command(CLI::App& app, const std::string& name, const std::string& description,
                            Options& o, int (*run)(const Options&)) {
  CLI::App* cmd = add_command(app, name, description, o, run);
  add_scene_options(*cmd, o.scene, false);
  add_backend_options(*cmd, o.choice, false);
  return cmd;
}
// Loads the file (or the defaults) and applies the overrides; errors name the key and range.
scene::SceneFile load_scene(const SceneChoice& choice);
// An option that sets the scene parameter `path` conflicts with `--set path=...`: throws naming
// both when the option was given (`given`) and a --set names the same parameter.
void refuse_set_conflict(const SceneChoice& choice, bool given, const std::string& option,
                         const std::string& path);
// The ffmpeg executable on PATH, or "" when there is none.
std::string find_ffmpeg();

}  // namespace masav::app
