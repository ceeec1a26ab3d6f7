#include "render/scene_player.h"

#include <fmt/format.h>
#include <imgui.h>

#include <algorithm>

#include "engine/core/error.h"
#include "registry/check_catalog.h"
#include "registry/scene_catalog.h"

namespace masav::render {

uint32_t frame_width(const scene::ParamSet& p) {
  return uint32_t(p.get_int("render.width"));
}
uint32_t frame_height(const scene::ParamSet& p) {
  return uint32_t(p.get_int("render.height"));
}

ScenePlayer::ScenePlayer(scene::SceneFile file, const PlayerOptions& options) : options_(options) {
  backend_ = open_compute_backend(options.backend, options.device, options.graphics, options.tuning,
                                  options.cache_dir);
  make_scene(std::move(file));
  render_device_ = std::make_unique<RenderDevice>(*backend_, options.graphics);
  // ImGui's 13 px font stays legible on large frames.
  const float scale = std::max(1.0f, float(frame_height(file_.params)) / 720.0f);
  ui_ = std::make_unique<UiContext>(std::floor(scale * 2.0f) / 2.0f);
  renderer_ = std::make_unique<Renderer>(*render_device_, *ui_, frame_width(file_.params),
                                         frame_height(file_.params));
}

ScenePlayer::~ScenePlayer() {
  // The renderer may borrow the backend's device and the scene holds the backend's buffers.
  renderer_.reset();
  render_device_.reset();
  scene_.reset();
  backend_.reset();
}

void check_render_params(const scene::ParamSet& p) {
  if (p.get_text("render.point_style") == "surface" && p.get_text("render.blend") == "additive")
    throw Error("", "render.point_style",
                "render.point_style = surface needs opaque points, but render.blend = additive",
                "set render.blend = \"opaque\" for the fluid surface, or choose "
                "render.point_style = sprites or spheres");
}

void ScenePlayer::make_scene(scene::SceneFile file) {
  check_render_params(file.params);
  const scene::SceneType& type = scene::find_scene_type(file.type);
  auto next =
      type.create(*backend_, file.params, scene::SceneHost{.cache_dir = options_.cache_dir});
  scene_ = std::move(next);
  file_ = std::move(file);
  clock_ = scene::FrameClock{};
  clock_.time_s = file_.params.get_real("run.start_time_s");
  clock_.dt_s = 1.0 / file_.params.get_real("run.fps");
}

void ScenePlayer::load_scene(scene::SceneFile file) {
  if (backend_) backend_->finish();
  make_scene(std::move(file));
  verify_status_.clear();
  progress_note_.clear();
  if (renderer_) renderer_->resize(frame_width(file_.params), frame_height(file_.params));
}

void ScenePlayer::reset() {
  load_scene(file_);
}

verify::CrossCheckReport ScenePlayer::verify() {
  // The reference computes only: the program's loader and validation, no window, its best device.
  vk::ContextOptions compute;
  compute.validation = options_.graphics.validation;
  compute.loader = options_.graphics.loader;
  compute.driver_files = options_.graphics.driver_files;
  compute.icd_filenames = options_.graphics.icd_filenames;
  auto reference =
      verify::open_reference(*backend_, scene_->params().get_text("verify.reference"),
                             BackendRequest{.vulkan = &compute, .cache_dir = options_.cache_dir});
  verify::CrossCheckReport r = verify::cross_check_scene(*backend_, *reference, scene_->params(), options_.fault);
  verify_status_ =
      r.pass() ? fmt::format("cross-check: {} kernels agree with {}", r.rows.size(), r.reference)
               : fmt::format("cross-check FAILED: {}", verify::failure_summary(r));
  return r;
}

scene::UpdateReport ScenePlayer::update() {
  return scene_->update(clock_, true);
}

OverlayInfo ScenePlayer::overlay(double fps, double frame_ms) const {
  OverlayInfo o;
  const scene::ParamSet& p = scene_->params();
  o.title = scene_->title();
  if (o.title.empty()) o.title = fmt::format("masav: {} scene", file_.type);
  o.backend = backend_->name();
  o.device = backend_->caps().device_name;
  if (!render_device_->shared()) o.render_device = render_device_->ctx().caps().device_name;
  o.frame = clock_.frame;
  o.time_s = clock_.time_s;
  o.simulated_time_s = scene_->simulated_time_s();
  o.fps = fps;
  o.frame_ms = frame_ms;
  o.progress = progress_note_;
  o.verify = verify_status_;
  const scene::SceneView v = scene_->view();
  if (v.points && !v.points->scalar_name.empty()) {
    const float shown = v.points->shown_per_unit;
    float lo = v.points->scalar_lo * shown, hi = v.points->scalar_hi * shown;
    if (!p.get_flag("render.auto_range"))
      lo = float(p.get_real("render.range_min")), hi = float(p.get_real("render.range_max"));
    o.legend = fmt::format("colour: {} from {:.3g} to {:.3g} ({})", v.points->scalar_name, lo, hi,
                           p.get_text("render.colormap"));
    const ColormapTable table = colormap_table(p.get_text("render.colormap"));
    o.colour_bar = ColourBar{v.points->scalar_name, lo, hi, {table.begin(), table.end()}};
  } else if (v.background && v.background->key) {
    const scene::ColourKey& k = *v.background->key;
    o.colour_bar = ColourBar{k.title, k.lo, k.hi, k.colours};
  }
  o.stages = scene_->graph().counters();
  return o;
}

void ScenePlayer::draw(FrameRequest extra, const std::function<void()>& build_ui, double fps,
                       double frame_ms) {
  const scene::SceneView view = scene_->view();
  ui_->make_current();
  if (platform_frame_) platform_frame_();
  ImGuiIO& io = ImGui::GetIO();
  io.DisplaySize = ImVec2(float(renderer_->width()), float(renderer_->height()));
  if (!platform_frame_) io.DeltaTime = float(frame_ms > 0 ? frame_ms * 1e-3 : clock_.dt_s);
  if (!(io.DeltaTime > 0)) io.DeltaTime = 1.0f / 60.0f;
  ImGui::NewFrame();
  if (scene_->params().get_flag("render.overlay")) {
    // The overlay belongs to the scene: clipped to its viewport when the frame has a panel.
    ImDrawList* fg = ImGui::GetForegroundDrawList();
    fg->PushClipRect(ImVec2(0, 0), extra.scene_width
                                       ? ImVec2(float(extra.scene_width), float(extra.scene_height))
                                       : io.DisplaySize);
    draw_overlay(overlay(fps, frame_ms));
    fg->PopClipRect();
  }
  if (build_ui) build_ui();
  ImGui::Render();
  extra.view = &view;
  extra.params = &scene_->params();
  extra.time_s = clock_.time_s;
  extra.ui = ImGui::GetDrawData();
  renderer_->render(extra);
}

}  // namespace masav::render
