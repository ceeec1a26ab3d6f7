// masav::SceneRenderer: render::ScenePlayer (what `masav run` steps frame by frame) behind the
// public API, with the options a library caller passes instead of the command line's
// environment. Without the renderer (a build without Vulkan) the constructor says so.
#include <fmt/format.h>

#include "engine/core/error.h"
#include "engine/io/png_writer.h"
#include "masav/scene_render.h"

#if MASAV_HAVE_RENDER
#include "render/render_device.h"
#include "render/scene_player.h"
#endif

namespace masav {

void save_png(const std::string& path, const Frame& frame) {
  if (frame.width == 0 || frame.height == 0 ||
      frame.rgba.size() != size_t(frame.width) * frame.height * 4)
    throw_invalid("masav::save_png", "frame",
                  fmt::format("{}x{} with {} bytes", frame.width, frame.height, frame.rgba.size()),
                  "width * height * 4 bytes, at least one pixel");
  write_png(path, frame.width, frame.height, frame.rgba);
}

#if MASAV_HAVE_RENDER

struct SceneRenderer::State {
  std::unique_ptr<render::ScenePlayer> player;
  uint64_t frames = 0;
};

namespace {

render::PlayerOptions player_options(const BackendOptions& compute, const RenderOptions& render) {
  render::PlayerOptions po;
  po.backend = compute.name;
  po.device = compute.device;
  po.tuning = compute.tuning;
  po.cache_dir = compute.cache_dir;
  vk::ContextOptions base;
  base.validation = compute.vulkan_validation;
  base.loader = compute.vulkan_loader;
  // A Vulkan compute backend draws on its own device (render_device.h); `auto` may resolve to
  // one, which open_compute_backend opens with these options too.
  po.graphics = render::graphics_options(base, compute.name == "vulkan" ? compute.device
                                                                         : render.device);
  return po;
}

}  // namespace

SceneRenderer::SceneRenderer(scene::SceneFile scene, const BackendOptions& compute,
                             const RenderOptions& render)
    : state_(std::make_unique<State>()) {
  state_->player =
      std::make_unique<render::ScenePlayer>(std::move(scene), player_options(compute, render));
}

SceneRenderer::~SceneRenderer() = default;

verify::CrossCheckReport SceneRenderer::verify() {
  return state_->player->verify();
}

Frame SceneRenderer::next_frame() {
  render::ScenePlayer& player = *state_->player;
  const scene::ParamSet& p = player.scene().params();
  const uint64_t i = state_->frames;
  player.clock().frame = i;
  player.clock().time_s = p.get_real("run.start_time_s") + double(i) / p.get_real("run.fps");
  player.update();
  render::FrameRequest request;
  request.readback = true;
  player.draw(request);
  ++state_->frames;
  return {player.renderer().width(), player.renderer().height(), player.renderer().pixels()};
}

uint64_t SceneRenderer::frames_drawn() const {
  return state_->frames;
}
uint32_t SceneRenderer::width() const {
  return state_->player->renderer().width();
}
uint32_t SceneRenderer::height() const {
  return state_->player->renderer().height();
}
std::string SceneRenderer::backend_name() const {
  return state_->player->backend().name();
}
std::string SceneRenderer::compute_device_name() const {
  return state_->player->backend().caps().device_name;
}
std::string SceneRenderer::render_device_name() const {
  return state_->player->render_device().ctx().caps().device_name;
}
bool SceneRenderer::shares_device() const {
  return state_->player->render_device().shared();
}

#else  // no renderer in this build

struct SceneRenderer::State {};

SceneRenderer::SceneRenderer(scene::SceneFile, const BackendOptions&, const RenderOptions&) {
  throw Error("", "masav::SceneRenderer", "this masav was built without Vulkan, which draws",
              "rebuild masav with -DMASAV_WITH_VULKAN=ON (libvulkan-dev, glslc)");
}
SceneRenderer::~SceneRenderer() = default;
verify::CrossCheckReport SceneRenderer::verify() {
  return {};
}
Frame SceneRenderer::next_frame() {
  return {};
}
uint64_t SceneRenderer::frames_drawn() const {
  return 0;
}
uint32_t SceneRenderer::width() const {
  return 0;
}
uint32_t SceneRenderer::height() const {
  return 0;
}
std::string SceneRenderer::backend_name() const {
  return {};
}
std::string SceneRenderer::compute_device_name() const {
  return {};
}
std::string SceneRenderer::render_device_name() const {
  return {};
}
bool SceneRenderer::shares_device() const {
  return false;
}

#endif

}  // namespace masav
