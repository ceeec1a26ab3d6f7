#pragma once
// The demo's ImGui panel (SPEC §3): scene, transport (pause/step/reset, dt), viewpoints and the
// orbit camera, backend switch, cross-check status, every parameter of the scene's tables (from
// their schemas), and per-stage timings. Requests that rebuild things (another scene or
// backend, a reset, a cross-check) are collected and applied between frames.
#include <optional>
#include <string>
#include <vector>

#include "render/scene_player.h"

namespace masav::app {

struct DemoRequests {
  std::optional<std::string> scene_file;
  std::optional<std::string> backend;
  bool reset = false;
  bool verify = false;
  bool quit = false;
};

struct DemoState {
  bool paused = false;
  bool step = false;
  bool show_panel = true;
  std::vector<std::string> scene_files;  // offered in the scene selector
  std::vector<std::string> backends;     // available compute backends
  std::string message;                   // the last error, shown until the next change
  double fps = 0, frame_ms = 0;
  DemoRequests requests;
};

// Changes a parameter as the panel does; an invalid value leaves the old one and sets message.
void set_param(render::ScenePlayer& player, DemoState& st, const std::string& path,
               const scene::ParamValue& v);
// The panel, plus mouse orbit/zoom on the scene when ImGui does not want the mouse.
void draw_panel(render::ScenePlayer& player, DemoState& st);

}  // namespace masav::app
