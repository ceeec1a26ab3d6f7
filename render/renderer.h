#pragma once
// Draws a scene's layers with Vulkan into an offscreen target: the background image a kernel
// computed (full-screen quad), the box and axes (lines), the particles (through a colour map:
// additive glows, or opaque flat sprites, lit sphere impostors with their own depth, or a
// screen-space fluid surface), then ImGui's draw data (overlay text and colour bar, the demo's
// panel). Headless runs read the frame back for PNGs; the demo blits it to the window.
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "engine/scene/param_schema.h"
#include "engine/scene/scene_view.h"
#include "render/camera.h"
#include "render/colormap.h"
#include "render/gfx_pipeline.h"
#include "render/layer_bridge.h"
#include "render/offscreen_target.h"
#include "render/render_device.h"
#include "render/ui_context.h"

struct ImDrawData;

namespace masav::render {

struct FrameRequest {
  const scene::SceneView* view = nullptr;   // null: only the UI
  const scene::ParamSet* params = nullptr;  // [render] and [camera]
  double time_s = 0;
  ImDrawData* ui = nullptr;  // ImGui draw data (after ImGui::Render()), or null
  bool readback = false;     // keep the pixels for pixels()
  // The scene's viewport, at the frame's top left (0: the whole frame). The demo draws the scene
  // beside its panel: the camera's aspect and the scene's layers follow this area, the UI the
  // whole frame.
  uint32_t scene_width = 0, scene_height = 0;
  // Commands recorded after the frame is drawn (the demo's blit to the swapchain) and the
  // semaphores of that submission.
  std::function<void(const ::vk::raii::CommandBuffer&, ::vk::Image color)> after;
  ::vk::Semaphore wait, signal;
  ::vk::PipelineStageFlags wait_stage;
};

// Additive sprites: render.brightness = 1 is a glow that shows the structure of 200K particles
// drawn 2 px wide in a frame 540 px high, seen from 0.9 box diagonals with a 40 degree field of
// view (the atom scenes' defaults; measured: state 8's lobes, torus and nodal cones stay
// unsaturated). Each sprite gets brightness x this weight, so that the count, the frame size,
// the sprite size and the zoom leave the picture's exposure as it is. `zoom` is the cloud's size
// on screen against that framing: (0.9 / camera.distance) x (tan 20 deg / tan(fov / 2)). A
// sprite keeps its pixel size at the camera's distance, so a closer camera spreads the same
// sprites over zoom^2 more pixels.
constexpr double kAdditiveGlow = 0.15;
constexpr double kAdditiveReferenceCount = 200000, kAdditiveReferenceHeightPx = 540,
                 kAdditiveReferenceSizePx = 2, kAdditiveReferenceDistance = 0.9,
                 kAdditiveReferenceFovDeg = 40;
float additive_weight(uint32_t count, uint32_t frame_height, float point_size_px, double zoom = 1);
// additive_weight's zoom for camera.distance (box diagonals) and a vertical field of view; at
// least 1 (a view from farther away keeps the reference framing's weight).
double additive_zoom(double distance_diagonals, double fov_y_deg);

class Renderer {
 public:
  Renderer(RenderDevice& dev, const UiContext& ui, uint32_t width, uint32_t height);
  ~Renderer();

  void resize(uint32_t width, uint32_t height);
  uint32_t width() const { return target_->width(); }
  uint32_t height() const { return target_->height(); }
  RenderDevice& device() const { return dev_; }
  const LayerBridge& bridge() const { return bridge_; }

  void render(const FrameRequest& frame);
  // RGBA8 rows of the last frame rendered with readback = true.
  std::vector<uint8_t> pixels() const { return target_->pixels(); }
  // The camera of the last frame (for tests projecting known points).
  const Camera& camera() const { return camera_; }

 private:
  ::vk::DescriptorSet bind(const GraphicsPipeline& p,
                           std::initializer_list<std::shared_ptr<vk::Allocation>> buffers);
  void draw_background(const ::vk::raii::CommandBuffer& cmd, const scene::ImageLayer& img);
  void draw_lines(const ::vk::raii::CommandBuffer& cmd, const scene::Box& box,
                  const scene::ParamSet& p, bool axes);
  void draw_points(const ::vk::raii::CommandBuffer& cmd, const scene::PointLayer& pts,
                   const scene::ParamSet& p);
  void draw_ui(const ::vk::raii::CommandBuffer& cmd, ImDrawData* data);
  // The fluid surface (render.point_style = surface): its planes cleared before the frame's
  // first pass, the points splatted into them (draw_points), then five more passes: the depth
  // smoothed along rows, columns, rows and columns again (one round alone leaves streaks along
  // its last direction where it stops at depth steps), then the surface shaded.
  enum class FluidPass : uint8_t { smooth, smooth_again, shade };
  bool wants_surface(const FrameRequest& f) const;
  void clear_fluid(const ::vk::raii::CommandBuffer& cmd);
  void draw_fluid(const ::vk::raii::CommandBuffer& cmd, const scene::ParamSet& p, FluidPass pass);
  std::shared_ptr<vk::Allocation> host_buffer(std::shared_ptr<vk::Allocation>& slot, size_t bytes,
                                              const char* label);

  RenderDevice& dev_;
  const UiContext& ui_;
  LayerBridge bridge_;
  ::vk::raii::RenderPass pass_ = nullptr, continue_pass_ = nullptr;
  std::unique_ptr<OffscreenTarget> target_;
  std::unique_ptr<GraphicsPipeline> points_opaque_, points_spheres_, points_additive_, lines_,
      axes_, image_, ui_pipe_, fluid_splat_, fluid_smooth_, fluid_shade_;
  ::vk::raii::DescriptorPool pool_ = nullptr;
  std::shared_ptr<vk::Allocation> colormap_, line_vertices_, axis_vertices_, ui_vertices_,
      ui_indices_, atlas_, dummy_, fluid_;
  std::string colormap_name_;
  std::vector<std::shared_ptr<vk::Allocation>> frame_buffers_;  // alive until the frame ends
  Camera camera_;
  uint32_t scene_w_ = 0, scene_h_ = 0;  // the scene's viewport in the frame being drawn
};

}  // namespace masav::render
