// What the demo is asked to do between frames: keyboard shortcuts and panel buttons (actions),
// the panel's requests (another scene, backend, a reset, a cross-check, a volume file), files
// dropped on the window, and the commands of a `--script` file, which the tests drive it with.
// Each is applied between frames (poll_keys, called while the panel is drawn, only queues).
#include <fmt/format.h>
#include <imgui.h>

#include <string>
#include <vector>

#include "app/demo/demo_app.h"
#include "engine/atom/orbital.h"
#include "engine/core/error.h"

namespace masav::app {

// One shortcut, button or script `key`/`button`.
void DemoApp::apply_action(const ActionRequest& a) {
  const scene::ParamSet& p = player_->scene().params();
  switch (a.action) {
    case Action::pause:
      state_.paused = !state_.paused;
      break;
    case Action::step:
      state_.step = true;
      state_.paused = true;
      break;
    case Action::reset:
      state_.requests.reset = true;
      break;
    case Action::preset:
      if (p.has_table("atom") && size_t(a.index) < atom::preset_names().size())
        set_param(*player_, state_, "atom.state", atom::preset_names()[size_t(a.index)]);
      else if (p.has_table("sph") && size_t(a.index) < p.spec("sph.preset").choices.size())
        set_param(*player_, state_, "sph.preset", p.spec("sph.preset").choices[size_t(a.index)]);
      else
        state_.message = fmt::format("no state or preset {} in this scene", a.index + 1);
      break;
    case Action::screenshot:
      screenshot_ = capture_.next_screenshot();
      break;
    case Action::record:
      if (capture_.recording()) {
        stop_recording();
      } else {
        capture_.start_recording();
        state_.recording = "recording to " + capture_.recording_dir();
        fmt::print("demo: {}\n", state_.recording);
      }
      break;
    case Action::save_scene: {
      const std::string path = capture_.save_scene(player_->scene().saved_params());
      state_.saved = "saved " + path;
      fmt::print("demo: saved the scene to {}\n", path);
      break;
    }
    case Action::panel:
      state_.show_panel = !state_.show_panel;
      break;
  }
}

void DemoApp::apply_actions() {
  const std::vector<ActionRequest> actions = std::move(state_.actions);
  state_.actions.clear();
  for (const ActionRequest& a : actions) {
    try {
      apply_action(a);
    } catch (const Error& e) {
      state_.message = e.what();
      fmt::print(stderr, "masav demo: {}\n", e.what());
    }
  }
}

void DemoApp::stop_recording() {
  state_.saved =
      "recorded " + capture_.stop_recording(player_->scene().params().get_real("run.fps"));
  state_.recording.clear();
  fmt::print("demo: {}\n", state_.saved);
}

// The keyboard shortcuts, unless a text field has the keyboard.
void DemoApp::poll_keys() {
  const ImGuiIO& io = ImGui::GetIO();
  if (io.WantTextInput) return;
  for (const Shortcut& k : shortcuts())
    if (ImGui::IsKeyPressed(k.key, false)) state_.actions.push_back(k.request);
}

// A file dropped on the window opens as the panel's "Open" would, with the panel's raw and
// .vti options; of several dropped at once, the last is opened.
void DemoApp::take_dropped_files() {
  const std::vector<std::string> dropped = window_.take_dropped_files();
  if (dropped.empty()) return;
  fmt::print("demo: {} file{} dropped, opening {}\n", dropped.size(),
             dropped.size() == 1 ? "" : "s", dropped.back());
  state_.open_fields.path = dropped.back();
  state_.requests.open_volume = state_.open_fields;
}

// A volume file that is refused (the checks of `masav volume`) leaves the current scene and
// says why in the panel; the demo, and a script driving it, go on.
void DemoApp::open_volume(const OpenFields& f) {
  try {
    show_scene(volume_scene_file(f));
    state_.message.clear();
    fmt::print("demo: opened {}: {}\n", f.path, player_->scene().title());
  } catch (const Error& e) {
    state_.message = e.what();
    fmt::print(stderr, "masav demo: cannot open {}: {}\n", f.path, e.what());
  }
}

void DemoApp::apply_requests() {
  DemoRequests& r = state_.requests;
  if (r.scene_file || r.backend || r.reset || r.open_volume) {
    restart_timing_ = true;
    state_.fps = state_.frame_ms = 0;
  }
  try {
    if (r.scene_file) show_scene(scene::load_scene_file(*r.scene_file));
    if (r.backend) {
      scene::SceneFile current = player_->file();
      current.params = player_->scene().params();
      const double t = player_->clock().time_s;
      stop();
      start(std::move(current), *r.backend);
      player_->clock().time_s = t;
    }
    if (r.reset) {
      player_->reset();
      forget_tf_scene(state_.tf);
      player_->renderer().resize(swapchain_->width(), swapchain_->height());
      device_defaults();
    }
    if (r.verify) verify(false);
    // A change that worked ends the last error's message; a frame without one keeps it.
    if (r.scene_file || r.backend || r.reset || r.verify) state_.message.clear();
  } catch (const Error& e) {
    state_.message = e.what();
    fmt::print(stderr, "masav demo: {}\n", e.what());
    if (!player_) throw;  // a backend switch that failed leaves nothing to show
    if (scripted_) failed_ = true;
  }
  // After the others, whose success clears the message: a refusal stays in the panel.
  if (r.open_volume) open_volume(*r.open_volume);
  r = DemoRequests{};
}

// Runs script commands up to the next one that needs a frame.
void DemoApp::run_script() {
  scripted_ = true;
  if (wait_frames_ > 0) {
    --wait_frames_;
    return;
  }
  while (next_ < script_.size()) {
    const ScriptCommand& c = script_[next_++];
    const std::string& a0 = c.args.empty() ? std::string() : c.args[0];
    if (c.verb == "wait") {
      wait_frames_ = std::stoi(a0) - 1;
      return;
    }
    if (c.verb == "screenshot") {
      screenshot_ = a0;
      return;
    }
    if (c.verb == "quit") break;
    if (c.verb == "set") {
      try {
        player_->scene().set_from_string(a0, c.args[1]);
      } catch (const Error& e) {
        throw Error("", fmt::format("{}:{}", options_.script, c.line), e.problem(), e.remedy());
      }
    } else if (c.verb == "view") {
      player_->scene().set("camera.view", a0);
    } else if (c.verb == "orbit") {
      player_->scene().set("camera.view", std::string("orbit"));
      player_->scene().set_from_string("camera.yaw_deg", a0);
      player_->scene().set_from_string("camera.pitch_deg", c.args[1]);
    } else if (c.verb == "scene") {
      state_.requests.scene_file = a0;
    } else if (c.verb == "backend") {
      state_.requests.backend = a0;
    } else if (c.verb == "pause") {
      state_.paused = true;
    } else if (c.verb == "resume") {
      state_.paused = false;
    } else if (c.verb == "step") {
      state_.step = true;
    } else if (c.verb == "reset") {
      state_.requests.reset = true;
    } else if (c.verb == "verify") {
      state_.requests.verify = true;
    } else if (c.verb == "panel") {
      state_.show_panel = a0 == "on";
    } else if (c.verb == "key") {
      state_.actions.push_back(*shortcut_by_name(a0));
    } else if (c.verb == "button") {
      state_.actions.push_back(*button_by_name(a0));
    } else if (c.verb == "open") {
      state_.open_fields =
          open_fields_from_words(c.args, fmt::format("{}:{}", options_.script, c.line));
      state_.requests.open_volume = state_.open_fields;
    } else if (c.verb == "drop") {
      std::vector<const char*> paths;
      for (const std::string& a : c.args) paths.push_back(a.c_str());
      window_.receive_drop(int(paths.size()), paths.data());
      take_dropped_files();
    } else if (c.verb == "rate") {
      state_.sim_rate = a0 == "off" ? 0.0 : std::stod(a0);
    } else if (c.verb == "progressive") {
      progressive_ = *progressive_mode_from_word(a0);
    } else if (c.verb == "tf") {
      const std::string said = run_tf_words(state_.tf, player_->scene(), c.args,
                                            fmt::format("{}:{}", options_.script, c.line));
      fmt::print("demo: tf {}: {}\n", a0, said);
    }
    apply_actions();
    apply_requests();
    if (failed_) {
      state_.requests.quit = true;
      return;
    }
  }
  if (next_ >= script_.size()) state_.requests.quit = true;
}

}  // namespace masav::app
