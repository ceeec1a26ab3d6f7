// `masav schema [type]`: every parameter of a scene type as a TOML file with its default, help
// and allowed range -- the reference of the scene-file format and a template to start from.
#include <fmt/format.h>

#include "app/commands.h"
#include "engine/scene/scene.h"
#include "registry/scene_catalog.h"
#include "registry/scene_file.h"

namespace masav::app {

void add_schema_command(CLI::App& app) {
  static std::string type = "particles";
  auto* cmd = app.add_subcommand("schema",
                                 "print every scene parameter with its default, "
                                 "help and allowed range (a scene-file template)");
  cmd->add_option("type", type, "scene type")
      ->check(CLI::IsMember(scene::scene_type_names()))
      ->capture_default_str();
  cmd->callback([] {
    const scene::SceneType& t = scene::find_scene_type(type);
    fmt::print("# masav scene '{}': {}\n# Every key is optional; shown with its default.\n\n",
               t.name, t.help);
    fmt::print("{}", scene::scene_to_toml(scene::default_params(t), true));
  });
}

}  // namespace masav::app
