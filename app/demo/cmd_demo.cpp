// `masav demo [scene.toml]`: the desktop demo -- a GLFW window showing the scene drawn with
// Vulkan, with an ImGui panel holding SPEC §3's controls. `--script FILE` drives it without a
// user (the tests run it under xvfb-run and inspect its screenshots).
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <fmt/format.h>
#include <imgui.h>

#include <chrono>
#include <filesystem>
#include <set>

#include "app/commands.h"
#include "app/demo/demo_panel.h"
#include "app/demo/demo_script.h"
#include "app/demo/demo_window.h"
#include "app/interrupt.h"
#include "app/scene_options.h"
#include "engine/core/error.h"
#include "registry/backends.h"
#include "render/png.h"
#include "render/swapchain.h"

namespace masav::app {
namespace {

struct DemoOptions {
  SceneChoice scene;
  BackendChoice choice;
  std::string script;
  bool no_verify = false;
};

// Scene files offered in the panel: those next to the current one and in ./scenes.
std::vector<std::string> find_scene_files(const std::string& current) {
  namespace fs = std::filesystem;
  std::set<std::string> files;
  if (!current.empty() && current.front() != '<') files.insert(current);
  std::vector<fs::path> dirs = {"scenes"};
  if (!current.empty() && current.front() != '<') dirs.push_back(fs::path(current).parent_path());
  for (const auto& d : dirs) {
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(d.empty() ? fs::path(".") : d, ec))
      if (e.path().extension() == ".toml") files.insert(e.path().lexically_normal().string());
  }
  return {files.begin(), files.end()};
}

class Demo {
 public:
  Demo(const DemoOptions& o, scene::SceneFile file)
      : options_(o),
        window_(uint32_t(file.params.get_int("render.width")),
                uint32_t(file.params.get_int("render.height")), "masav demo") {
    state_.scene_files = find_scene_files(file.source);
    for (const auto& s : list_backends())
      if (s.available) state_.backends.push_back(s.name);
    if (!o.script.empty()) script_ = load_script(o.script);
    start(std::move(file), o.choice.backend);
  }

  ~Demo() { stop(); }

  int loop() {
    auto last = std::chrono::steady_clock::now();
    while (!window_.should_close() && !state_.requests.quit && !interrupted()) {
      glfwPollEvents();
      if (!script_.empty() || scripted_) run_script();
      if (state_.requests.quit) break;
      apply_requests();
      if (!frame()) continue;
      const auto now = std::chrono::steady_clock::now();
      if (restart_timing_) {  // a new scene or backend: its frame rate starts from its own frames
        restart_timing_ = false;
        state_.fps = state_.frame_ms = 0;
        last = now;
        continue;
      }
      state_.frame_ms = std::chrono::duration<double, std::milli>(now - last).count();
      state_.fps =
          state_.fps == 0 ? 1e3 / state_.frame_ms : 0.9 * state_.fps + 0.1 * 1e3 / state_.frame_ms;
      last = now;
    }
    return failed_ ? 1 : 0;
  }

 private:
  // Opens the backend, the renderer on a device that can present, the swapchain and ImGui's
  // window-system hooks.
  void start(scene::SceneFile file, const std::string& backend) {
    render::PlayerOptions po;
    po.backend = backend;
    po.device = options_.choice.device;
    po.graphics = window_.graphics_options(backend == "vulkan" ? options_.choice.device : "");
    player_ = std::make_unique<render::ScenePlayer>(std::move(file), po);
    uint32_t w = 0, h = 0;
    window_.framebuffer_size(w, h);
    swapchain_ = std::make_unique<render::Swapchain>(
        player_->render_device().ctx(), window_.create_surface(player_->render_device().ctx()), w,
        h);
    player_->renderer().resize(swapchain_->width(), swapchain_->height());
    player_->ui().make_current();
    ImGui_ImplGlfw_InitForVulkan(window_.handle(), true);
    player_->set_platform_frame([] { ImGui_ImplGlfw_NewFrame(); });
    window_.set_title(fmt::format("masav demo: {} on {} ({})", player_->file().type,
                                  player_->backend().name(),
                                  player_->backend().caps().device_name));
    fmt::print("demo: '{}' on {} ({}), drawn on {}\n", player_->file().source,
               player_->backend().name(), player_->backend().caps().device_name,
               player_->render_device().ctx().caps().device_name);
    if (!options_.no_verify && player_->scene().params().get_flag("verify.enabled"))
      verify(true);
    else
      player_->set_verify_status("cross-check skipped (--no-verify)");
  }

  void stop() {
    if (!player_) return;
    player_->ui().make_current();
    ImGui_ImplGlfw_Shutdown();
    swapchain_.reset();
    player_.reset();
  }

  void verify(bool stop_on_failure) {
    const verify::CrossCheckReport r = player_->verify();
    fmt::print("{}", verify::format_report(r));
    if (!r.pass() && stop_on_failure)
      throw Error("", "cross-check", fmt::format("{}; the demo stops", verify::failure_summary(r)),
                  "report the device and driver; --no-verify shows the scene anyway");
  }

  void apply_requests() {
    DemoRequests& r = state_.requests;
    if (r.scene_file || r.backend || r.reset) {
      restart_timing_ = true;
      state_.fps = state_.frame_ms = 0;
    }
    try {
      if (r.scene_file) {
        player_->load_scene(scene::load_scene_file(*r.scene_file));
        state_.scene_files = find_scene_files(player_->file().source);
        player_->renderer().resize(swapchain_->width(), swapchain_->height());
        if (!options_.no_verify) verify(false);
      }
      if (r.backend) {
        scene::SceneFile current = player_->file();
        current.params = player_->scene().params();
        const double t = player_->clock().time_s;
        stop();
        start(std::move(current), *r.backend);
        player_->clock().time_s = t;
      }
      if (r.reset) player_->reset();
      if (r.verify) verify(false);
      state_.message.clear();
    } catch (const Error& e) {
      state_.message = e.what();
      fmt::print(stderr, "masav demo: {}\n", e.what());
      if (!player_) throw;  // a backend switch that failed leaves nothing to show
      if (scripted_) failed_ = true;
    }
    r = DemoRequests{};
  }

  // Runs script commands up to the next one that needs a frame.
  void run_script() {
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
      }
      apply_requests();
      if (failed_) {
        state_.requests.quit = true;
        return;
      }
    }
    if (next_ >= script_.size()) state_.requests.quit = true;
  }

  // One frame: advance the clock, update the stages, draw, present. False if skipped.
  bool frame() {
    uint32_t w = 0, h = 0;
    window_.framebuffer_size(w, h);
    if (w == 0 || h == 0) {  // minimised
      glfwWaitEventsTimeout(0.1);
      return false;
    }
    if (w != swapchain_->width() || h != swapchain_->height()) {
      swapchain_->recreate(w, h);
      player_->renderer().resize(swapchain_->width(), swapchain_->height());
    }
    // render.width/height (panel, script or a new scene) size the window.
    const scene::ParamSet& p = player_->scene().params();
    const int want_w = int(p.get_int("render.width")), want_h = int(p.get_int("render.height"));
    if (want_w != window_w_ || want_h != window_h_) {
      if (window_w_ != 0) glfwSetWindowSize(window_.handle(), want_w, want_h);
      window_w_ = want_w;
      window_h_ = want_h;
    }
    scene::FrameClock& clock = player_->clock();
    if (!state_.paused || state_.step) {
      clock.time_s += 1.0 / player_->scene().params().get_real("run.fps");
      ++clock.frame;
      state_.step = false;
    }
    try {
      player_->update();
    } catch (const Error& e) {
      state_.message = e.what();
      state_.paused = true;
    }
    if (!swapchain_->acquire()) {
      swapchain_->recreate(w, h);
      return false;
    }
    render::FrameRequest req;
    req.readback = !screenshot_.empty();
    req.wait = swapchain_->image_available();
    req.wait_stage = ::vk::PipelineStageFlagBits::eTransfer;
    req.signal = swapchain_->render_finished();
    req.after = [this](const ::vk::raii::CommandBuffer& cmd, ::vk::Image color) {
      swapchain_->record_blit(cmd, color, player_->renderer().width(),
                              player_->renderer().height());
    };
    player_->draw(
        req, [this] { draw_panel(*player_, state_); }, state_.fps, state_.frame_ms);
    if (!swapchain_->present()) swapchain_->recreate(w, h);
    if (!screenshot_.empty()) {
      render::write_png(screenshot_, player_->renderer().width(), player_->renderer().height(),
                        player_->renderer().pixels());
      // What the overlay showed on it: the title and the clock line (the tests read them).
      const std::vector<std::string> shown = render::overlay_lines(player_->overlay());
      fmt::print("demo: wrote {}: {} | {}\n", screenshot_, shown[0], shown[1]);
      screenshot_.clear();
    }
    return true;
  }

  DemoOptions options_;
  DemoWindow window_;
  std::unique_ptr<render::ScenePlayer> player_;
  std::unique_ptr<render::Swapchain> swapchain_;
  DemoState state_;
  std::vector<ScriptCommand> script_;
  size_t next_ = 0;
  int wait_frames_ = 0;
  int window_w_ = 0, window_h_ = 0;  // the size render.width/height last asked for
  bool scripted_ = false;
  bool failed_ = false;
  bool restart_timing_ = false;  // the next frame's time includes loading a scene: not counted
  std::string screenshot_;
};

int run_demo(const DemoOptions& o) {
  scene::SceneFile file = load_scene(o.scene);
  if (!o.script.empty()) (void)load_script(o.script);  // report script errors before the window
  install_interrupt_handler();
  Demo demo(o, std::move(file));
  return demo.loop();
}

}  // namespace

void add_demo_command(CLI::App& app) {
  static DemoOptions o;
  auto* cmd = add_scene_command(app, "demo",
                                "the desktop demo: the scene in a window with a control "
                                "panel (needs a display; `masav run` renders headless)",
                                o, run_demo);
  cmd->add_option("--script", o.script,
                  "drive the demo from a script (wait N, set K V, view V, scene F, backend B, "
                  "pause, step, reset, verify, panel on|off, screenshot F, quit)");
  cmd->add_flag("--no-verify", o.no_verify, "start without the cross-check");
}

}  // namespace masav::app
