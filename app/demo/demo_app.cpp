// The demo's loop and its frame: the backend and the renderer started (and stopped, to switch),
// a scene shown at its viewport's size, the frame drawn and presented with the panel, the
// simulated time paced to the rate asked for, the preview level chosen, and what the tests read
// beside a screenshot. What the user and a script ask for is in demo_requests.cpp.
#define GLFW_INCLUDE_NONE
#include "app/demo/demo_app.h"

#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <fmt/format.h>
#include <imgui.h>

#include <algorithm>
#include <cfloat>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>

#include "app/demo/idle_wait.h"
#include "app/host_environment.h"
#include "app/interrupt.h"
#include "engine/core/error.h"
#include "engine/sph/sph_scene_type.h"
#include "engine/sph/sph_simulation.h"
#include "engine/util/output_file.h"
#include "registry/backends.h"
#include "render/png.h"

namespace masav::app {
namespace {

// Steps of a stepped scene's frame are capped at this much device time, so the window stays
// responsive when the rate asked for is more than the device can do.
constexpr double kStepBudgetMs = 60.0;

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

}  // namespace

DemoApp::DemoApp(const DemoOptions& o, scene::SceneFile file, uint32_t window_w, uint32_t window_h)
    : options_(o), window_(window_w, window_h, "masav demo"), capture_(o.out) {
  state_.scene_files = find_scene_files(file.source);
  for (const auto& s : list_backends(HostRequest(host_environment()).get()))
    if (s.available) state_.backends.push_back(s.name);
  if (!o.script.empty()) script_ = load_script(o.script);
  uint32_t w = 0, h = 0;
  window_.framebuffer_size(w, h);
  fmt::print("demo: window {}x{} (screen work area {}x{})\n", w, h, window_.work_width(),
             window_.work_height());
  // The scene starts at its viewport's size and the UI scale that size gives.
  const float scale = std::max(1.0f, std::floor(2.0f * float(std::max(h, 1u)) / 720.0f) / 2.0f);
  state_.layout = make_layout(w, h, state_.show_panel, scale);
  fit_to_viewport(file.params);
  start(std::move(file), o.choice.backend);
}

DemoApp::~DemoApp() {
  stop();
}

int DemoApp::loop() {
  auto last = std::chrono::steady_clock::now();
  while (!window_.should_close() && !state_.requests.quit && !interrupted()) {
    IdleInputs idle;
    idle.quiet_frames = quiet_frames_;
    idle.scripted = !script_.empty() || scripted_;
    idle.recording = capture_.recording();
    idle.actions_queued = !state_.actions.empty();
    const double wait_s = idle_wait_seconds(idle);
    const auto wait_start = std::chrono::steady_clock::now();
    if (wait_s > 0)
      glfwWaitEventsTimeout(wait_s);
    else
      glfwPollEvents();
    // The frame time counts the work, not the wait for input.
    last += std::chrono::steady_clock::now() - wait_start;
    take_dropped_files();
    if (!script_.empty() || scripted_) run_script();
    if (state_.requests.quit) break;
    apply_actions();
    apply_requests();
    if (!frame()) continue;
    const auto now = std::chrono::steady_clock::now();
    const std::optional<double> sim_t = player_->scene().simulated_time_s();
    if (restart_timing_) {  // a new scene or backend: its frame rate starts from its own frames
      restart_timing_ = false;
      state_.fps = state_.frame_ms = 0;
      rate_.reset();
      moving_level_ = first_preview_level(state_.device_class, scene::kMaxPreviewLevel);
      last = now;
      last_sim_t_ = sim_t;
      continue;
    }
    state_.frame_ms = std::chrono::duration<double, std::milli>(now - last).count();
    state_.fps =
        state_.fps == 0 ? 1e3 / state_.frame_ms : 0.9 * state_.fps + 0.1 * 1e3 / state_.frame_ms;
    if (sim_t && last_sim_t_ && *sim_t >= *last_sim_t_)
      rate_.add(*sim_t - *last_sim_t_, state_.frame_ms * 1e-3);
    else
      rate_.reset();  // a restart (preset, integrator) went back in time
    state_.sim_rate_achieved = rate_.rate();
    last_sim_t_ = sim_t;
    last = now;
  }
  if (capture_.recording()) stop_recording();
  return failed_ ? 1 : 0;
}

// Opens the backend, the renderer on a device that can present, the swapchain and ImGui's
// window-system hooks.
void DemoApp::start(scene::SceneFile file, const std::string& backend) {
  render::PlayerOptions po;
  po.backend = backend;
  po.device = options_.choice.device;
  po.tuning = options_.choice.tuning();
  po.fault = fault_kernel(options_.choice);
  po.graphics = window_.graphics_options(backend == "vulkan" ? options_.choice.device : "");
  po.cache_dir = host_environment().cache_dir().string();
  player_ = std::make_unique<render::ScenePlayer>(std::move(file), po);
  forget_tf_scene(state_.tf);
  uint32_t w = 0, h = 0;
  window_.framebuffer_size(w, h);
  swapchain_ = std::make_unique<render::Swapchain>(
      player_->render_device().ctx(), window_.create_surface(player_->render_device().ctx()), w, h);
  player_->renderer().resize(swapchain_->width(), swapchain_->height());
  player_->ui().make_current();
  ImGui_ImplGlfw_InitForVulkan(window_.handle(), true);
  // A scripted run ignores the pointer, wherever the X server left it: no hover, no tooltip.
  const bool scripted = !options_.script.empty();
  player_->set_platform_frame([scripted] {
    ImGui_ImplGlfw_NewFrame();
    if (scripted) ImGui::GetIO().MousePos = ImVec2(-FLT_MAX, -FLT_MAX);
  });
  window_.set_title(fmt::format("masav demo: {} on {} ({})", player_->file().type,
                                player_->backend().name(), player_->backend().caps().device_name));
  fmt::print("demo: '{}' on {} ({}), drawn on {}\n", player_->file().source,
             player_->backend().name(), player_->backend().caps().device_name,
             player_->render_device().ctx().caps().device_name);
  const SimRateDefaults d = sim_rate_defaults(player_->backend().caps().device_type);
  state_.sim_rate = d.seconds_per_second;
  state_.device_class = d.device_class;
  moving_level_ = first_preview_level(state_.device_class, scene::kMaxPreviewLevel);
  device_defaults();
  if (!options_.no_verify && player_->scene().params().get_flag("verify.enabled"))
    verify(true);
  else
    player_->set_verify_status("cross-check skipped (--no-verify)");
}

void DemoApp::stop() {
  if (!player_) return;
  player_->ui().make_current();
  ImGui_ImplGlfw_Shutdown();
  swapchain_.reset();
  player_.reset();
}

// render.width/height of a scene shown here: its viewport.
void DemoApp::fit_to_viewport(scene::ParamSet& p) const {
  p.set("render.width", int64_t(state_.layout.scene_w));
  p.set("render.height", int64_t(state_.layout.scene_h));
}

// An SPH scene on a CPU device starts with fewer particles, so that it moves at once -- unless the
// scene file or --set gave sph.count (a value other than the default has a version above 0).
void DemoApp::device_defaults() {
  if (player_->file().type != "sph") return;
  const SimRateDefaults d = sim_rate_defaults(player_->backend().caps().device_type);
  const scene::ParamSet& p = player_->scene().params();
  const int64_t count = p.get_int("sph.count");
  fmt::print("demo: {} s simulated per second by default on a {}\n", d.seconds_per_second,
             d.device_class);
  const bool given = p.version("sph.count") != 0;
  const uint32_t start = demo_particle_count(uint32_t(count), given, d.max_particles);
  if (start == count) {
    if (given && d.max_particles && count > int64_t(d.max_particles))
      fmt::print("demo: sph.count {} as given (fewer particles step faster on a {})\n", count,
                 d.device_class);
    return;
  }
  set_param(*player_, state_, "sph.count", int64_t(start));
  fmt::print("demo: sph.count {} -> {} on a {} (set sph.count for more)\n", count, start,
             d.device_class);
}

void DemoApp::verify(bool stop_on_failure) {
  const verify::CrossCheckReport r = player_->verify();
  fmt::print("{}", verify::format_report(r));
  if (!r.pass() && stop_on_failure)
    throw Error("", "cross-check", fmt::format("{}; the demo stops", verify::failure_summary(r)),
                "report the device and driver; --no-verify shows the scene anyway");
}

// Shows another scene on the same backend; on error the current one stays.
void DemoApp::show_scene(scene::SceneFile next) {
  fit_to_viewport(next.params);
  player_->load_scene(std::move(next));
  forget_tf_scene(state_.tf);
  state_.scene_files = find_scene_files(player_->file().source);
  player_->renderer().resize(swapchain_->width(), swapchain_->height());
  device_defaults();
  if (!options_.no_verify) verify(false);
}

// Steps per frame of a stepped scene for the simulated time per second asked for.
void DemoApp::pace_simulation() {
  const SphSimulation* sim = sph::simulation_of(player_->scene());
  if (!sim || state_.paused || state_.sim_rate <= 0) return;  // 0: the scene's own substeps
  const scene::ParamSet& p = player_->scene().params();
  const int64_t steps_now = p.get_int("sph.substeps");
  double step_ms = 0;
  for (const auto& c : player_->scene().graph().counters())
    if (c.name == "step" && c.runs > 0)
      step_ms = c.last_ms / double(std::max<int64_t>(1, steps_now));
  const double dt = sim->last_dt() > 0 ? sim->last_dt() : sim->dt_limit();
  const double frame_s = state_.frame_ms > 0 ? state_.frame_ms * 1e-3 : 1.0 / 30;
  const uint32_t steps = steps_for_rate(state_.sim_rate, frame_s, dt, step_ms, kStepBudgetMs,
                                        uint32_t(p.spec("sph.substeps").int_max));
  if (int64_t(steps) != steps_now) player_->scene().set("sph.substeps", int64_t(steps));
}

// One frame: advance the clock, update the stages, draw, present. False if skipped.
bool DemoApp::frame() {
  uint32_t w = 0, h = 0;
  window_.framebuffer_size(w, h);
  if (w == 0 || h == 0) {  // minimised
    glfwWaitEventsTimeout(0.1);
    return false;
  }
  if (w != swapchain_->width() || h != swapchain_->height()) swapchain_->recreate(w, h);
  if (player_->renderer().width() != swapchain_->width() ||
      player_->renderer().height() != swapchain_->height())
    player_->renderer().resize(swapchain_->width(), swapchain_->height());
  // The scene's viewport: the frame less the panel; the scene renders at that size.
  state_.layout = make_layout(swapchain_->width(), swapchain_->height(), state_.show_panel,
                              ImGui::GetIO().FontGlobalScale);
  const scene::ParamSet& p = player_->scene().params();
  if (p.get_int("render.width") != int64_t(state_.layout.scene_w))
    player_->scene().set("render.width", int64_t(state_.layout.scene_w));
  if (p.get_int("render.height") != int64_t(state_.layout.scene_h))
    player_->scene().set("render.height", int64_t(state_.layout.scene_h));
  pace_simulation();
  scene::FrameClock& clock = player_->clock();
  if (!state_.paused || state_.step) {
    clock.time_s += 1.0 / player_->scene().params().get_real("run.fps");
    ++clock.frame;
    state_.step = false;
  }
  choose_preview_level();
  try {
    quiet_frames_ = player_->update().ran.empty() ? quiet_frames_ + 1 : 0;
  } catch (const Error& e) {
    quiet_frames_ = 0;
    // A simulation that stops (the SPH watchdog, a NaN) keeps its last good state on screen:
    // the demo pauses there and shows why, in the panel and on stderr.
    state_.message = e.what();
    if (!state_.paused) fmt::print(stderr, "masav demo: paused: {}\n", e.what());
    state_.paused = true;
  }
  if (!swapchain_->acquire()) {
    swapchain_->recreate(w, h);
    return false;
  }
  render::FrameRequest req;
  req.readback = !screenshot_.empty() || capture_.recording();
  req.scene_width = state_.layout.scene_w;
  req.scene_height = state_.layout.scene_h;
  req.wait = swapchain_->image_available();
  req.wait_stage = ::vk::PipelineStageFlagBits::eTransfer;
  req.signal = swapchain_->render_finished();
  req.after = [this](const ::vk::raii::CommandBuffer& cmd, ::vk::Image color) {
    swapchain_->record_blit(cmd, color, player_->renderer().width(), player_->renderer().height());
  };
  player_->draw(
      req,
      [this] {
        poll_keys();
        draw_panel(*player_, state_);
      },
      state_.fps, state_.frame_ms);
  if (!swapchain_->present()) swapchain_->recreate(w, h);
  if (!screenshot_.empty()) {
    render::write_png(screenshot_, player_->renderer().width(), player_->renderer().height(),
                      player_->renderer().pixels());
    // What the overlay showed on it: the title and the clock line (the tests read them).
    const std::vector<std::string> shown = render::overlay_lines(player_->overlay());
    fmt::print("demo: wrote {}: {} | {}\n", screenshot_, shown[0], shown[1]);
    if (!state_.message.empty())
      fmt::print("demo: the panel shows at {}: {}\n", screenshot_, state_.message);
    write_layout(screenshot_ + ".layout");
    if (player_->scene().max_preview_level() > 0) {
      // The level and the times of the frame, and whether a still scene raymarched at all.
      const scene::StageCounters& rm = player_->scene().graph().counters("raymarch");
      std::string stages;
      for (const scene::StageCounters& c : player_->scene().graph().counters())
        if (c.created) stages += fmt::format(" {} {:.1f}", c.name, c.last_ms);
      fmt::print(
          "demo: {} at {}: {:.1f} fps, last frame {:.1f} ms, raymarch {:.1f} ms, {} "
          "raymarch runs since the last screenshot; stages' last runs (ms):{}\n",
          preview_label(player_->scene().preview_level()), screenshot_, state_.fps, state_.frame_ms,
          rm.last_ms, rm.runs - std::min(rm.runs, shot_raymarch_runs_), stages);
      shot_raymarch_runs_ = rm.runs;
    }
    if (sph::simulation_of(player_->scene()))
      fmt::print("demo: rate at {}: asked {} s/s, achieved {:.3g} s/s, {} steps per frame\n",
                 screenshot_, state_.sim_rate > 0 ? fmt::format("{}", state_.sim_rate) : "off",
                 state_.sim_rate_achieved, player_->scene().params().get_int("sph.substeps"));
    screenshot_.clear();
  }
  if (capture_.recording())
    render::write_png(capture_.next_frame(), player_->renderer().width(),
                      player_->renderer().height(), player_->renderer().pixels());
  return true;
}

// Progressive rendering: the preview level of this frame's raymarch, from whether anything
// changes and from the last frame's times; the overlay names it.
void DemoApp::choose_preview_level() {
  scene::SceneInstance& s = player_->scene();
  if (s.max_preview_level() == 0) {
    player_->set_progress_note("");
    return;
  }
  const scene::StageCounters& rm = s.graph().counters("raymarch");
  LevelInputs in;
  in.moving = progressive_.enabled && s.changes_pending(player_->clock());
  in.level = s.preview_level();
  in.frame_ms = state_.frame_ms;
  in.raymarch_ms = rm.runs != raymarch_runs_ ? rm.last_ms : 0;  // 0: none ran last frame
  in.max_level = s.max_preview_level();
  in.first_level = moving_level_;
  uint32_t level = next_preview_level(in);
  if (in.moving && progressive_.fixed_level > 0) level = progressive_.fixed_level;
  if (in.moving) moving_level_ = level;
  s.set_preview_level(level);
  raymarch_runs_ = rm.runs;
  player_->set_progress_note(preview_label(s.preview_level()));
}

// The rectangles of the frame just written (x y width height), for the tests.
void DemoApp::write_layout(const std::string& path) const {
  const DemoLayout& l = state_.layout;
  write_output(path,
               fmt::format("window 0 0 {} {}\nscene 0 0 {} {}\npanel {} 0 {} {}\nexpanded {}\n",
                           l.window_w, l.window_h, l.scene_w, l.scene_h, l.panel_x, l.panel_w,
                           l.window_h, l.expanded ? 1 : 0),
               "the screenshot's layout");
}

}  // namespace masav::app
