#pragma once
// The desktop demo as one object (`masav demo`, cmd_demo.cpp): a GLFW window, the scene player on
// a backend with the renderer on a device that can present, the swapchain, the panel's state,
// and the loop that draws frames until the window closes, the script ends or the user quits.
// demo_app.cpp holds the loop, the frame and the backend's start and stop; demo_requests.cpp what
// shortcuts, the panel, dropped files and a script ask for.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "app/commands.h"
#include "app/demo/demo_capture.h"
#include "app/demo/demo_panel.h"
#include "app/demo/demo_script.h"
#include "app/demo/demo_window.h"
#include "app/demo/progressive.h"
#include "app/demo/sim_rate.h"
#include "app/scene_options.h"
#include "registry/scene_file.h"
#include "render/scene_player.h"
#include "render/swapchain.h"

namespace masav::app {

struct DemoOptions {
  SceneChoice scene;
  BackendChoice choice;
  std::string script;
  std::string window;  // WxH, or "" to fit the screen
  std::string out = "out/demo";
  bool no_verify = false;
};

class DemoApp {
 public:
  DemoApp(const DemoOptions& o, scene::SceneFile file, uint32_t window_w, uint32_t window_h);
  ~DemoApp();
  DemoApp(const DemoApp&) = delete;
  DemoApp& operator=(const DemoApp&) = delete;

  // Draws frames until the window closes, the script ends or the user quits; the exit status.
  int loop();

 private:
  // demo_app.cpp
  void start(scene::SceneFile file, const std::string& backend);
  void stop();
  void fit_to_viewport(scene::ParamSet& p) const;
  void device_defaults();
  void verify(bool stop_on_failure);
  void show_scene(scene::SceneFile next);
  void pace_simulation();
  bool frame();
  void choose_preview_level();
  void write_layout(const std::string& path) const;

  // demo_requests.cpp
  void apply_action(const ActionRequest& a);
  void apply_actions();
  void stop_recording();
  void poll_keys();
  void take_dropped_files();
  void open_volume(const OpenFields& f);
  void apply_requests();
  void run_script();

  DemoOptions options_;
  uint32_t quiet_frames_ = 0;  // consecutive frames whose update ran no stage
  DemoWindow window_;
  std::unique_ptr<render::ScenePlayer> player_;
  std::unique_ptr<render::Swapchain> swapchain_;
  DemoCapture capture_;
  DemoState state_;
  RateMeter rate_;
  std::optional<double> last_sim_t_;
  std::vector<ScriptCommand> script_;
  size_t next_ = 0;
  int wait_frames_ = 0;
  bool scripted_ = false;
  bool failed_ = false;
  bool restart_timing_ = false;  // the next frame's time includes loading a scene: not counted
  std::string screenshot_;
  ProgressiveMode progressive_;
  uint32_t moving_level_ = 0;   // the level of the last moving frame: where the next motion starts
  uint64_t raymarch_runs_ = 0;  // the raymarch stage's runs as of the last level choice
  uint64_t shot_raymarch_runs_ = 0;  // and as of the last screenshot
};

}  // namespace masav::app
