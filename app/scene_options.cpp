#include "app/scene_options.h"

#include <fmt/format.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <sstream>

#include "engine/core/error.h"
#include "engine/util/json_writer.h"

namespace masav::app {

void add_scene_options(CLI::App& cmd, SceneChoice& choice, bool path_required) {
  auto* opt = cmd.add_option("scene", choice.path,
                             "scene file (TOML; scenes/ holds the shipped ones, `masav schema` "
                             "prints every parameter)");
  if (path_required) opt->required();
  cmd.add_option("--set", choice.sets,
                 "override a parameter: --set table.key=value (repeatable), e.g. "
                 "--set particles.count=10000");
}

scene::SceneFile load_scene(const SceneChoice& choice) {
  scene::SceneFile f =
      choice.path.empty() ? scene::default_scene("particles") : scene::load_scene_file(choice.path);
  for (const auto& s : choice.sets) {
    const auto eq = s.find('=');
    if (eq == std::string::npos || eq == 0)
      throw_invalid("--set", "--set", s, "table.key=value, e.g. particles.count=10000");
    f.params.set_from_string(s.substr(0, eq), s.substr(eq + 1));
  }
  return f;
}

void refuse_set_conflict(const SceneChoice& choice, bool given, const std::string& option,
                         const std::string& path) {
  if (!given) return;
  for (const auto& s : choice.sets)
    if (s.rfind(path + "=", 0) == 0)
      throw Error("", option,
                  fmt::format("{} conflicts with --set {}: both set {}", option, s, path),
                  fmt::format("give one of {} and --set {}=...", option, path));
}


std::string find_ffmpeg() {
  const char* path = std::getenv("PATH");
  if (!path) return "";
  std::stringstream ss(path);
  std::string dir;
  while (std::getline(ss, dir, ':')) {
    if (dir.empty()) continue;
    const std::string candidate = dir + "/ffmpeg";
    if (::access(candidate.c_str(), X_OK) == 0) return candidate;
  }
  return "";
}

}  // namespace masav::app
