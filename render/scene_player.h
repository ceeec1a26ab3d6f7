#pragma once
// A scene being played on a compute backend and drawn with Vulkan: the backend, the scene's
// stages, the renderer and the UI context, and the clock. `masav run` steps it frame by frame
// into PNGs; the demo drives it from the window and its panel (and can switch the scene or the
// backend under it).
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "engine/scene/scene.h"
#include "engine/verify/cross_check.h"
#include "registry/scene_file.h"
#include "render/overlay.h"
#include "render/renderer.h"

namespace masav::render {

struct PlayerOptions {
  std::string backend = "auto";
  std::string device;
  vk::ContextOptions graphics;  // render context options (the demo adds window extensions)
  Tuning tuning;                // the compute backend's (--tune)
  // The disk caches' directory (engine/util/cache_dir.h: the Vulkan pipeline cache, the atom
  // scenes' scattering table); "" = none, each run recomputes.
  std::string cache_dir;
  std::optional<KernelId> fault;  // perturbed in verify() (the tests' --inject-fault)
};

class ScenePlayer {
 public:
  ScenePlayer(scene::SceneFile file, const PlayerOptions& options);
  ~ScenePlayer();

  scene::SceneInstance& scene() { return *scene_; }
  const scene::SceneFile& file() const { return file_; }
  Backend& backend() { return *backend_; }
  Renderer& renderer() { return *renderer_; }
  RenderDevice& render_device() { return *render_device_; }
  const UiContext& ui() const { return *ui_; }
  scene::FrameClock& clock() { return clock_; }

  // Replaces the scene (same backend and renderer). On error the old scene stays.
  void load_scene(scene::SceneFile file);
  // Re-creates the scene at its file's parameters and time zero.
  void reset();

  // Runs the cross-check of the scene's kernels against the second backend (verify.reference).
  verify::CrossCheckReport verify();
  const std::string& verify_status() const { return verify_status_; }
  // The window system's per-frame input hook (ImGui_ImplGlfw_NewFrame), run before each
  // ImGui frame; without one, the frame's display size and time step are set here.
  void set_platform_frame(std::function<void()> fn) { platform_frame_ = std::move(fn); }
  void set_verify_status(std::string s) { verify_status_ = std::move(s); }
  // A line the overlay shows under the clock (the demo's progressive level); "" = none.
  void set_progress_note(std::string s) { progress_note_ = std::move(s); }

  // Brings the stages up to date for the clock's time (with per-stage device times).
  scene::UpdateReport update();
  // Draws the current state: the overlay (if render.overlay), `build_ui` (the demo's panel),
  // then the frame. `extra` carries readback and the window's blit and semaphores.
  void draw(FrameRequest extra, const std::function<void()>& build_ui = {}, double fps = 0,
            double frame_ms = 0);
  // What the overlay shows now (fps and frame_ms as the window measured them).
  OverlayInfo overlay(double fps = 0, double frame_ms = 0) const;

 private:
  void make_scene(scene::SceneFile file);

  PlayerOptions options_;
  scene::SceneFile file_;
  std::unique_ptr<Backend> backend_;
  std::unique_ptr<scene::SceneInstance> scene_;
  std::unique_ptr<RenderDevice> render_device_;
  std::unique_ptr<UiContext> ui_;
  std::unique_ptr<Renderer> renderer_;
  scene::FrameClock clock_;
  std::string verify_status_;
  std::string progress_note_;
  std::function<void()> platform_frame_;
};

// Throws for render parameters that contradict each other (naming both and what to change).
void check_render_params(const scene::ParamSet& p);

// The frame size a scene asks for.
uint32_t frame_width(const scene::ParamSet& p);
uint32_t frame_height(const scene::ParamSet& p);

}  // namespace masav::render
