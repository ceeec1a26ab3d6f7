#pragma once
// The demo's ImGui panel (SPEC §3), beside the scene's viewport: scene, transport
// (pause/step/reset, dt), capture (screenshot, record, save), viewpoints and the orbit camera,
// backend switch, cross-check status, every parameter of the scene's tables (from their
// schemas), per-stage timings and the keyboard shortcuts. Collapsed, it is a strip with the button
// that expands it. Requests that rebuild things (another scene or
// backend, a reset, a cross-check) are collected and applied between frames.
#include <optional>
#include <string>
#include <vector>

#include "app/demo/demo_actions.h"
#include "app/demo/demo_layout.h"
#include "app/demo/tf_points.h"
#include "app/demo/volume_open.h"
#include "render/scene_player.h"

namespace masav::app {

struct DemoRequests {
  std::optional<std::string> scene_file;
  std::optional<std::string> backend;
  std::optional<OpenFields> open_volume;  // "Open", a dropped file or the script's `open`
  bool reset = false;
  bool verify = false;
  bool quit = false;
};

struct DemoState {
  bool paused = false;
  bool step = false;
  bool show_panel = true;                // expanded; false: collapsed to a strip
  DemoLayout layout;                     // this frame's scene viewport and panel
  std::vector<std::string> scene_files;  // offered in the scene selector
  std::vector<std::string> backends;     // available compute backends
  OpenFields open_fields;                // the panel's "open a volume file" fields
  TfEditorState tf;                      // the transfer function editor (tf_editor.h)
  std::string message;                   // the last error, shown until the next change
  std::string saved;                     // the last file the demo wrote, shown until the next
  std::string recording;                 // "" or what is being recorded, where
  double fps = 0, frame_ms = 0;
  // Stepped scenes (SPH): simulated seconds per wall-clock second asked for and achieved.
  double sim_rate = 0, sim_rate_achieved = 0;
  std::string device_class;  // "CPU device" or "GPU": where the rate's default comes from
  DemoRequests requests;
  std::vector<ActionRequest> actions;  // buttons pressed this frame, applied between frames
};

// Changes a parameter as the panel does; an invalid value leaves the old one and sets message.
void set_param(render::ScenePlayer& player, DemoState& st, const std::string& path,
               const scene::ParamValue& v);
// The panel, plus mouse orbit/zoom on the scene when ImGui does not want the mouse.
void draw_panel(render::ScenePlayer& player, DemoState& st);

}  // namespace masav::app
