#pragma once
// Draws a scene's layers with Vulkan into an offscreen target: the background image a kernel
// computed (full-screen quad), the box and axes (lines), the particles (point sprites through a
// colour map, depth-tested), then ImGui's draw data (overlay text, the demo's panel). Headless
// runs read the frame back for PNGs; the demo blits it to the window.
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
  std::shared_ptr<vk::Allocation> host_buffer(std::shared_ptr<vk::Allocation>& slot, size_t bytes,
                                              const char* label);

  RenderDevice& dev_;
  const UiContext& ui_;
  LayerBridge bridge_;
  ::vk::raii::RenderPass pass_ = nullptr;
  std::unique_ptr<OffscreenTarget> target_;
  std::unique_ptr<GraphicsPipeline> points_opaque_, points_additive_, lines_, axes_, image_,
      ui_pipe_;
  ::vk::raii::DescriptorPool pool_ = nullptr;
  std::shared_ptr<vk::Allocation> colormap_, line_vertices_, axis_vertices_, ui_vertices_,
      ui_indices_, atlas_, dummy_;
  std::string colormap_name_;
  std::vector<std::shared_ptr<vk::Allocation>> frame_buffers_;  // alive until the frame ends
  Camera camera_;
  uint32_t scene_w_ = 0, scene_h_ = 0;  // the scene's viewport in the frame being drawn
};

}  // namespace masav::render
