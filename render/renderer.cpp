#include "render/renderer.h"

#include <fmt/format.h>
#include <imgui.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>

#include "engine/core/error.h"

namespace masav::render {
namespace {

constexpr uint32_t kSetsPerFrame = 16;

struct PointsPush {
  glm::mat4 view_proj;
  float size[4];
  float range[4];
  uint32_t mode[4];
  float eye[4];  // the camera, and the world radius of the sphere a sprite stands for
};
static_assert(sizeof(PointsPush) <= 128);

struct ImagePush {
  uint32_t shape[4];
  float tone[4];
};

struct FluidSmoothPush {
  uint32_t shape[4];
  float sphere[4];
};

struct FluidShadePush {
  uint32_t shape[4];
  float proj[4];
  float look[4];
};

// shaders/render/fluid_common.glsl: the planes, and those the smoothing reads and writes.
constexpr uint32_t kFluidPlanes = 8, kFluidNearest = 0, kFluidSmoothed = 1, kFluidAcross = 7;
// The smoothing filter's standard deviation and depth range, in sphere radii: a lattice's
// bumps (within a radius of each other) merge, a drop three radii in front does not.
constexpr float kFluidFilterRadii = 1.5f, kFluidDepthRadii = 2.0f;
constexpr uint32_t kFluidEmptyBits = 0x7F61B1E6u;  // 3.0e38f, the shaders' kEmpty

struct UiPush {
  float transform[4];
  uint32_t offsets[4];
};

struct LineVertex {
  float position[4];
  float color[4];
};

static_assert(sizeof(ImDrawIdx) == 2, "the UI shader unpacks 16-bit indices");
static_assert(sizeof(ImDrawVert) == 20, "the UI shader reads five words per vertex");

}  // namespace

float additive_weight(uint32_t count, uint32_t frame_height, float point_size_px, double zoom) {
  // Glows add up where the sprites overlap, about count x sprite area / the cloud's area in
  // pixels (which grows as the frame height squared and the zoom squared) of them per pixel.
  const double overlap = double(count) / kAdditiveReferenceCount *
                         std::pow(double(point_size_px) / kAdditiveReferenceSizePx, 2.0) /
                         std::pow(double(frame_height) / kAdditiveReferenceHeightPx * zoom, 2.0);
  // A few sprites in a large frame glow no brighter than opaque ones.
  return float(std::min(1.0, kAdditiveGlow / std::max(overlap, 1e-12)));
}

double additive_zoom(double distance_diagonals, double fov_y_deg) {
  constexpr double kDegToRad = 3.14159265358979323846 / 180.0;
  const double zoom = kAdditiveReferenceDistance / std::max(distance_diagonals, 1e-6) *
                      std::tan(0.5 * kAdditiveReferenceFovDeg * kDegToRad) /
                      std::tan(0.5 * std::clamp(fov_y_deg, 1.0, 179.0) * kDegToRad);
  // Views from farther away keep the reference framing's weight: their clouds are small on
  // screen, and a dimmer glow would lose them.
  return std::max(zoom, 1.0);
}

Renderer::Renderer(RenderDevice& dev, const UiContext& ui, uint32_t width, uint32_t height)
    : dev_(dev), ui_(ui), bridge_(dev) {
  const vk::Context& ctx = dev.ctx();
  pass_ = make_render_pass(ctx);
  target_ = std::make_unique<OffscreenTarget>(ctx, *pass_, width, height);
  using T = ::vk::PrimitiveTopology;
  GraphicsSpec points{
      "render/points.vert", "render/points.frag", 3, sizeof(PointsPush), T::ePointList, true, true,
      Blend::none};
  points_opaque_ = make_graphics_pipeline(ctx, *pass_, points);
  GraphicsSpec spheres = points;
  spheres.frag = "render/spheres.frag";
  points_spheres_ = make_graphics_pipeline(ctx, *pass_, spheres);
  continue_pass_ = make_render_pass(ctx, true);
  if (ctx.fragment_stores()) {
    GraphicsSpec splat = points;
    splat.frag = "render/fluid_splat.frag";
    splat.buffers = 4;
    splat.depth_test = splat.depth_write = false;
    splat.color_write = false;
    fluid_splat_ = make_graphics_pipeline(ctx, *pass_, splat);
    fluid_smooth_ = make_graphics_pipeline(
        ctx, *pass_,
        {"render/fullscreen.vert", "render/fluid_smooth.frag", 1, sizeof(FluidSmoothPush),
         T::eTriangleList, false, false, Blend::none, false});
    fluid_shade_ = make_graphics_pipeline(
        ctx, *pass_,
        {"render/fullscreen.vert", "render/fluid_shade.frag", 1, sizeof(FluidShadePush),
         T::eTriangleList, true, true, Blend::alpha});
  }
  points.depth_write = false;
  points.blend = Blend::additive;
  points_additive_ = make_graphics_pipeline(ctx, *pass_, points);
  lines_ = make_graphics_pipeline(ctx, *pass_,
                                  {"render/lines.vert", "render/lines.frag", 1, sizeof(glm::mat4),
                                   T::eLineList, true, true, Blend::alpha});
  // The axes are drawn over the particles so that the orientation always shows.
  axes_ = make_graphics_pipeline(ctx, *pass_,
                                 {"render/lines.vert", "render/lines.frag", 1, sizeof(glm::mat4),
                                  T::eLineList, false, false, Blend::alpha});
  // The image as texel buffers (rgba8 words, rgba32f pixels): lavapipe fetches a texel with a
  // gather, where it loads a storage buffer's element in a loop over the lanes.
  image_ = make_graphics_pipeline(ctx, *pass_,
                                  {"render/image.vert",
                                   "render/image.frag",
                                   2,
                                   sizeof(ImagePush),
                                   T::eTriangleList,
                                   false,
                                   false,
                                   Blend::none,
                                   true,
                                   {vk::kTexelsR32u, vk::kTexelsRgba32f}});
  // The font atlas, read by every fragment of the panel and the overlay, as a texel buffer too.
  ui_pipe_ = make_graphics_pipeline(ctx, *pass_,
                                    {"render/ui.vert",
                                     "render/ui.frag",
                                     3,
                                     sizeof(UiPush),
                                     T::eTriangleList,
                                     false,
                                     false,
                                     Blend::alpha,
                                     true,
                                     {vk::kStorageBuffer, vk::kStorageBuffer, vk::kTexelsR32u}});
  const ::vk::DescriptorPoolSize sizes[] = {
      {::vk::DescriptorType::eStorageBuffer, 4 * kSetsPerFrame},
      {::vk::DescriptorType::eUniformTexelBuffer, 2 * kSetsPerFrame}};
  pool_ = ::vk::raii::DescriptorPool(ctx.device(),
                                     ::vk::DescriptorPoolCreateInfo({}, kSetsPerFrame, sizes));
  dummy_ = vk::allocate(ctx, 16, vk::MemoryUse::upload, "render placeholder");
  std::memset(dummy_->mapped, 0, 16);
  atlas_ = vk::allocate(ctx, ui.atlas().size() * 4, vk::MemoryUse::upload, "font atlas");
  std::memcpy(atlas_->mapped, ui.atlas().data(), ui.atlas().size() * 4);
}

Renderer::~Renderer() = default;

void Renderer::resize(uint32_t width, uint32_t height) {
  if (width == target_->width() && height == target_->height()) return;
  dev_.device().waitIdle();
  target_ = std::make_unique<OffscreenTarget>(dev_.ctx(), *pass_, width, height);
}

std::shared_ptr<vk::Allocation> Renderer::host_buffer(std::shared_ptr<vk::Allocation>& slot,
                                                      size_t bytes, const char* label) {
  if (!slot || slot->bytes < bytes)
    slot = vk::allocate(dev_.ctx(), std::max<size_t>(bytes, 4096) * 3 / 2, vk::MemoryUse::upload,
                        label);
  return slot;
}

::vk::DescriptorSet Renderer::bind(const GraphicsPipeline& p,
                                   std::initializer_list<std::shared_ptr<vk::Allocation>> buffers) {
  const ::vk::DescriptorSetLayout layout = *p.set_layout;
  const ::vk::DescriptorSet set =
      (*dev_.device())
          .allocateDescriptorSets(::vk::DescriptorSetAllocateInfo(*pool_, layout),
                                  *dev_.device().getDispatcher())
          .front();
  std::vector<::vk::DescriptorBufferInfo> infos;
  std::vector<::vk::BufferView> views(buffers.size());
  for (const auto& b : buffers) {
    infos.emplace_back(*b->buffer, 0, VK_WHOLE_SIZE);
    frame_buffers_.push_back(b);
  }
  std::vector<::vk::WriteDescriptorSet> writes;
  uint32_t i = 0;
  for (const auto& b : buffers) {
    const vk::Texels t = i < p.texels.size() ? p.texels[i] : vk::Texels{};
    if (t.descriptor_type() == ::vk::DescriptorType::eUniformTexelBuffer) {
      views[i] = vk::texel_view(dev_.ctx(), *b, t.format, t.bytes, "render");
      writes.emplace_back(set, i, 0, 1, t.descriptor_type(), nullptr, nullptr, &views[i]);
    } else {
      writes.emplace_back(set, i, 0, 1, t.descriptor_type(), nullptr, &infos[i]);
    }
    ++i;
  }
  dev_.device().updateDescriptorSets(writes, {});
  return set;
}

void Renderer::draw_background(const ::vk::raii::CommandBuffer& cmd, const scene::ImageLayer& img) {
  if (!img.pixels || img.width == 0 || img.height == 0) return;
  const size_t per_pixel = img.format == scene::ImageLayer::Format::rgba8 ? 1 : 4;
  // A real4 buffer (the raymarch's image) holds four values per element.
  const size_t values = img.pixels->count() * (img.pixels->kind() == ElemKind::real4 ? 4 : 1);
  if (values < size_t(img.width) * img.height * per_pixel)
    throw Error("render", "background",
                fmt::format("image buffer '{}' holds {} values, {}x{} "
                            "pixels need {}",
                            img.pixels->label(), values, img.width, img.height,
                            size_t(img.width) * img.height * per_pixel),
                "internal error: the scene's image layer does not match its buffer");
  const auto pixels = bridge_.words("background", *img.pixels, img.version);
  // The binding of the other format gets the placeholder (image.frag reads only the one).
  const bool rgba8 = img.format == scene::ImageLayer::Format::rgba8;
  const ::vk::DescriptorSet set = bind(*image_, {rgba8 ? pixels : dummy_, rgba8 ? dummy_ : pixels});
  const ImagePush push{
      {img.width, img.height, img.format == scene::ImageLayer::Format::rgba8 ? 0u : 1u,
       img.mono ? 1u : 0u},
      {img.gain, img.gamma, float(scene_w_), float(scene_h_)}};
  cmd.bindPipeline(::vk::PipelineBindPoint::eGraphics, *image_->pipeline);
  cmd.bindDescriptorSets(::vk::PipelineBindPoint::eGraphics, *image_->layout, 0, set, {});
  cmd.pushConstants<ImagePush>(
      *image_->layout, ::vk::ShaderStageFlagBits::eVertex | ::vk::ShaderStageFlagBits::eFragment, 0,
      push);
  cmd.draw(3, 1, 0, 0);
}

void Renderer::draw_lines(const ::vk::raii::CommandBuffer& cmd, const scene::Box& box,
                          const scene::ParamSet& p, bool axes) {
  std::vector<LineVertex> v;
  auto line = [&](const float a[3], const float b[3], const float c[4]) {
    v.push_back({{a[0], a[1], a[2], 1}, {c[0], c[1], c[2], c[3]}});
    v.push_back({{b[0], b[1], b[2], 1}, {c[0], c[1], c[2], c[3]}});
  };
  const float lo[3] = {box.lo.x, box.lo.y, box.lo.z}, hi[3] = {box.hi.x, box.hi.y, box.hi.z};
  if (!axes && p.get_flag("render.show_box")) {
    const float grey[4] = {0.75f, 0.75f, 0.8f, 0.8f};
    for (int axis = 0; axis < 3; ++axis)
      for (int corner = 0; corner < 4; ++corner) {
        float a[3], b[3];
        const int u = (axis + 1) % 3, w = (axis + 2) % 3;
        a[axis] = lo[axis], b[axis] = hi[axis];
        a[u] = b[u] = (corner & 1) ? hi[u] : lo[u];
        a[w] = b[w] = (corner & 2) ? hi[w] : lo[w];
        line(a, b, grey);
      }
  }
  if (axes && p.get_flag("render.show_axes")) {
    const float len = 0.25f * std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
    const float colors[3][4] = {{1, 0.25f, 0.25f, 1}, {0.3f, 1, 0.3f, 1}, {0.35f, 0.5f, 1, 1}};
    for (int axis = 0; axis < 3; ++axis) {
      float b[3] = {lo[0], lo[1], lo[2]};
      b[axis] += len;
      line(lo, b, colors[axis]);
    }
  }
  if (v.empty()) return;
  // Box edges are depth-tested against the particles; the axes are drawn over them, so the
  // orientation always shows.
  const GraphicsPipeline& pipe = axes ? *axes_ : *lines_;
  const auto buf = host_buffer(axes ? axis_vertices_ : line_vertices_,
                               v.size() * sizeof(LineVertex), axes ? "axes" : "box");
  std::memcpy(buf->mapped, v.data(), v.size() * sizeof(LineVertex));
  const ::vk::DescriptorSet set = bind(pipe, {buf});
  cmd.bindPipeline(::vk::PipelineBindPoint::eGraphics, *pipe.pipeline);
  cmd.bindDescriptorSets(::vk::PipelineBindPoint::eGraphics, *pipe.layout, 0, set, {});
  cmd.pushConstants<glm::mat4>(
      *pipe.layout, ::vk::ShaderStageFlagBits::eVertex | ::vk::ShaderStageFlagBits::eFragment, 0,
      camera_.view_proj);
  cmd.draw(uint32_t(v.size()), 1, 0, 0);
}

void Renderer::draw_points(const ::vk::raii::CommandBuffer& cmd, const scene::PointLayer& pts,
                           const scene::ParamSet& p) {
  if (!pts.positions || pts.count == 0) return;
  if (pts.positions->size() < pts.count)
    throw Error(
        "render", "points",
        fmt::format("{} points drawn from a buffer of {}", pts.count, pts.positions->size()),
        "internal error: the scene's point layer does not match its buffer");
  const std::string& map = p.get_text("render.colormap");
  if (map != colormap_name_) {
    const ColormapTable table = colormap_table(map);
    colormap_ = vk::allocate(dev_.ctx(), sizeof(table), vk::MemoryUse::upload, "colour map");
    std::memcpy(colormap_->mapped, table.data(), sizeof(table));
    colormap_name_ = map;
  }
  const auto positions = bridge_.positions("positions", *pts.positions, pts.count, pts.version);
  std::shared_ptr<vk::Allocation> scalars = dummy_;
  uint32_t mode = 0;
  using From = scene::PointLayer::ScalarFrom;
  if (pts.from == From::buffer && pts.scalar) {
    scalars = bridge_.words("scalars", *pts.scalar, pts.version);
    mode = pts.scalar->kind() == ElemKind::u32 ? 1u : 2u;
  } else if (pts.from == From::position_w) {
    mode = 3;
  } else if (pts.from == From::position_z) {
    mode = 4;
  } else if (pts.from == From::vector_length && pts.scalar) {
    scalars = bridge_.words("scalars", *pts.scalar, pts.version);
    mode = 5;
  }
  const uint32_t marker = pts.marker_below_w ? 1u : 0u;
  const uint32_t marker_w = std::bit_cast<uint32_t>(pts.marker_below_w.value_or(0.0f));
  float lo = pts.scalar_lo, hi = pts.scalar_hi;
  if (!p.get_flag("render.auto_range")) {  // given in the legend's units
    lo = float(p.get_real("render.range_min")) / pts.shown_per_unit;
    hi = float(p.get_real("render.range_max")) / pts.shown_per_unit;
  }
  const bool additive = p.get_text("render.blend") == "additive";
  const float size_px = float(p.get_real("render.point_size"));
  const float brightness = float(p.get_real("render.brightness")) *
                           (additive ? additive_weight(pts.count, height(), size_px,
                                                       additive_zoom(p.get_real("camera.distance"),
                                                                     p.get_real("camera.fov_deg")))
                                     : 1.0f);
  const std::string& style = p.get_text("render.point_style");
  const GraphicsPipeline& pipe = additive             ? *points_additive_
                                 : style == "sprites" ? *points_opaque_
                                                      : *points_spheres_;
  // A sprite point_size px wide at the camera's distance stands for a sphere of this radius.
  const float radius =
      0.5f * size_px * 2.0f * camera_.distance / (std::abs(camera_.proj[1][1]) * float(height()));
  const bool surface = !additive && style == "surface";
  const GraphicsPipeline& used = surface ? *fluid_splat_ : pipe;
  const ::vk::DescriptorSet set = surface ? bind(used, {positions, scalars, colormap_, fluid_})
                                          : bind(used, {positions, scalars, colormap_});
  const PointsPush push{camera_.view_proj,
                        {size_px, camera_.distance, dev_.ctx().max_point_size(), brightness},
                        {lo, hi, additive ? 1.0f : 0.0f, float(height())},
                        {mode, marker, marker_w, width()},
                        {camera_.eye.x, camera_.eye.y, camera_.eye.z, radius}};
  cmd.bindPipeline(::vk::PipelineBindPoint::eGraphics, *used.pipeline);
  cmd.bindDescriptorSets(::vk::PipelineBindPoint::eGraphics, *used.layout, 0, set, {});
  cmd.pushConstants<PointsPush>(
      *used.layout, ::vk::ShaderStageFlagBits::eVertex | ::vk::ShaderStageFlagBits::eFragment, 0,
      push);
  cmd.draw(pts.count, 1, 0, 0);
}

bool Renderer::wants_surface(const FrameRequest& f) const {
  return f.view && f.params && f.view->points && f.view->points->positions &&
         f.view->points->count > 0 && f.params->get_text("render.blend") != "additive" &&
         f.params->get_text("render.point_style") == "surface";
}

void Renderer::clear_fluid(const ::vk::raii::CommandBuffer& cmd) {
  const vk::Context& ctx = dev_.ctx();
  if (!fluid_splat_)
    throw Error("render", "render.point_style",
                fmt::format("the fluid surface writes storage buffers from fragment shaders, "
                            "which {} does not support (fragmentStoresAndAtomics)",
                            ctx.caps().device_name),
                "set render.point_style = \"spheres\" on this device");
  const uint64_t plane = uint64_t(width()) * height() * 4;
  const uint64_t bytes = plane * kFluidPlanes;
  const uint64_t limit = ctx.caps().max_buffer_bytes;
  if (limit && bytes > limit)
    throw Error("render", "render.point_style",
                fmt::format("the fluid surface of a {}x{} frame needs {} MiB in one buffer, {} "
                            "holds at most {} MiB",
                            width(), height(), bytes >> 20, ctx.caps().device_name, limit >> 20),
                fmt::format("lower render.width x render.height to at most {} pixels, or set "
                            "render.point_style = \"spheres\"",
                            limit / (4 * kFluidPlanes)));
  if (!fluid_ || fluid_->bytes < bytes)
    fluid_ = vk::allocate(ctx, bytes, vk::MemoryUse::device, "fluid surface planes");
  cmd.fillBuffer(*fluid_->buffer, 0, plane, kFluidEmptyBits);
  cmd.fillBuffer(*fluid_->buffer, plane, bytes - plane, 0u);
  const ::vk::MemoryBarrier filled(
      ::vk::AccessFlagBits::eTransferWrite,
      ::vk::AccessFlagBits::eShaderRead | ::vk::AccessFlagBits::eShaderWrite);
  cmd.pipelineBarrier(::vk::PipelineStageFlagBits::eTransfer,
                      ::vk::PipelineStageFlagBits::eFragmentShader, {}, filled, {}, {});
}

void Renderer::draw_fluid(const ::vk::raii::CommandBuffer& cmd, const scene::ParamSet& p,
                          FluidPass pass) {
  const bool shade = pass == FluidPass::shade;
  const float size_px = float(p.get_real("render.point_size"));
  const float focal_px = 0.5f * std::abs(camera_.proj[1][1]) * float(height());
  const float radius = 0.5f * size_px * camera_.distance / focal_px;
  const GraphicsPipeline& pipe = shade ? *fluid_shade_ : *fluid_smooth_;
  const ::vk::DescriptorSet set = bind(pipe, {fluid_});
  cmd.bindPipeline(::vk::PipelineBindPoint::eGraphics, *pipe.pipeline);
  cmd.bindDescriptorSets(::vk::PipelineBindPoint::eGraphics, *pipe.layout, 0, set, {});
  const auto stages = ::vk::ShaderStageFlagBits::eVertex | ::vk::ShaderStageFlagBits::eFragment;
  if (shade) {
    const FluidShadePush push{
        {width(), height(), 0, 0},
        {camera_.proj[0][0], camera_.proj[1][1], camera_.proj[2][2], camera_.proj[3][2]},
        {radius, float(p.get_real("render.brightness")), 0, 0}};
    cmd.pushConstants<FluidShadePush>(*pipe.layout, stages, 0, push);
  } else {
    // Two rounds, kFluidNearest into kFluidAcross into kFluidSmoothed, with the width split
    // between them (variances add).
    const bool first = pass == FluidPass::smooth;
    const FluidSmoothPush push{
        {width(), height(), first ? kFluidNearest : kFluidAcross,
         first ? kFluidAcross : kFluidSmoothed},
        {radius, focal_px, kFluidFilterRadii / std::sqrt(2.0f), kFluidDepthRadii}};
    cmd.pushConstants<FluidSmoothPush>(*pipe.layout, stages, 0, push);
  }
  cmd.draw(3, 1, 0, 0);
}

void Renderer::draw_ui(const ::vk::raii::CommandBuffer& cmd, ImDrawData* data) {
  if (!data || data->TotalVtxCount == 0) return;
  const size_t vbytes = size_t(data->TotalVtxCount) * sizeof(ImDrawVert);
  const size_t ibytes = (size_t(data->TotalIdxCount) * sizeof(ImDrawIdx) + 3) / 4 * 4;
  const auto vb = host_buffer(ui_vertices_, vbytes, "ui vertices");
  const auto ib = host_buffer(ui_indices_, ibytes, "ui indices");
  auto* vdst = static_cast<uint8_t*>(vb->mapped);
  auto* idst = static_cast<uint8_t*>(ib->mapped);
  for (int n = 0; n < data->CmdListsCount; ++n) {
    const ImDrawList* list = data->CmdLists[n];
    std::memcpy(vdst, list->VtxBuffer.Data, size_t(list->VtxBuffer.Size) * sizeof(ImDrawVert));
    std::memcpy(idst, list->IdxBuffer.Data, size_t(list->IdxBuffer.Size) * sizeof(ImDrawIdx));
    vdst += size_t(list->VtxBuffer.Size) * sizeof(ImDrawVert);
    idst += size_t(list->IdxBuffer.Size) * sizeof(ImDrawIdx);
  }
  const ::vk::DescriptorSet set = bind(*ui_pipe_, {vb, ib, atlas_});
  cmd.bindPipeline(::vk::PipelineBindPoint::eGraphics, *ui_pipe_->pipeline);
  cmd.bindDescriptorSets(::vk::PipelineBindPoint::eGraphics, *ui_pipe_->layout, 0, set, {});
  const float sx = 2.0f / data->DisplaySize.x, sy = 2.0f / data->DisplaySize.y;
  UiPush push{{sx, sy, -1.0f - data->DisplayPos.x * sx, -1.0f - data->DisplayPos.y * sy},
              {0, 0, ui_.atlas_width(), ui_.atlas_height()}};
  uint32_t vtx_base = 0, idx_base = 0;
  const float w = float(width()), h = float(height());
  for (int n = 0; n < data->CmdListsCount; ++n) {
    const ImDrawList* list = data->CmdLists[n];
    for (const ImDrawCmd& c : list->CmdBuffer) {
      if (c.UserCallback) continue;  // masav's panel adds none
      const float x0 = std::clamp(c.ClipRect.x - data->DisplayPos.x, 0.0f, w);
      const float y0 = std::clamp(c.ClipRect.y - data->DisplayPos.y, 0.0f, h);
      const float x1 = std::clamp(c.ClipRect.z - data->DisplayPos.x, 0.0f, w);
      const float y1 = std::clamp(c.ClipRect.w - data->DisplayPos.y, 0.0f, h);
      if (x1 <= x0 || y1 <= y0) continue;
      cmd.setScissor(
          0, ::vk::Rect2D({int32_t(x0), int32_t(y0)},
                          {uint32_t(x1 - float(int32_t(x0))), uint32_t(y1 - float(int32_t(y0)))}));
      push.offsets[0] = idx_base + c.IdxOffset;
      push.offsets[1] = vtx_base + c.VtxOffset;
      cmd.pushConstants<UiPush>(
          *ui_pipe_->layout,
          ::vk::ShaderStageFlagBits::eVertex | ::vk::ShaderStageFlagBits::eFragment, 0, push);
      cmd.draw(c.ElemCount, 1, 0, 0);
    }
    vtx_base += uint32_t(list->VtxBuffer.Size);
    idx_base += uint32_t(list->IdxBuffer.Size);
  }
  cmd.setScissor(0, ::vk::Rect2D({0, 0}, {width(), height()}));
}

void Renderer::render(const FrameRequest& f) {
  // Kernel outputs must be complete before they are drawn (or copied).
  dev_.compute().finish();
  pool_.reset();
  frame_buffers_.clear();
  const uint32_t scene_w = f.scene_width ? std::min(f.scene_width, width()) : width();
  const uint32_t scene_h = f.scene_height ? std::min(f.scene_height, height()) : height();
  scene_w_ = scene_w;
  scene_h_ = scene_h;
  const float aspect = float(scene_w) / float(scene_h);
  if (f.view && f.params) camera_ = make_camera(*f.params, f.view->box, aspect, f.time_s);

  const bool surface = wants_surface(f);
  const auto& cmd = dev_.begin();
  // Compute writes (same queue, earlier submissions) become visible to the draws.
  const ::vk::MemoryBarrier from_compute(::vk::AccessFlagBits::eShaderWrite |
                                             ::vk::AccessFlagBits::eTransferWrite |
                                             ::vk::AccessFlagBits::eHostWrite,
                                         ::vk::AccessFlagBits::eShaderRead);
  cmd.pipelineBarrier(
      ::vk::PipelineStageFlagBits::eComputeShader | ::vk::PipelineStageFlagBits::eTransfer |
          ::vk::PipelineStageFlagBits::eHost,
      ::vk::PipelineStageFlagBits::eVertexShader | ::vk::PipelineStageFlagBits::eFragmentShader, {},
      from_compute, {}, {});
  if (surface) clear_fluid(cmd);
  const ::vk::ClearValue clears[2] = {
      ::vk::ClearColorValue(std::array<float, 4>{0.02f, 0.02f, 0.04f, 1.0f}),
      ::vk::ClearDepthStencilValue(1.0f, 0)};
  auto begin_pass = [&](::vk::RenderPass pass) {
    cmd.beginRenderPass(::vk::RenderPassBeginInfo(pass, target_->framebuffer(),
                                                  {{0, 0}, {width(), height()}}, clears),
                        ::vk::SubpassContents::eInline);
    cmd.setViewport(0, ::vk::Viewport(0, 0, float(scene_w), float(scene_h), 0, 1));
    cmd.setScissor(0, ::vk::Rect2D({0, 0}, {scene_w, scene_h}));
  };
  begin_pass(*pass_);
  if (f.view && f.params) {
    if (f.view->background) draw_background(cmd, *f.view->background);
    draw_lines(cmd, f.view->box, *f.params, false);
    if (f.view->points) draw_points(cmd, *f.view->points, *f.params);
    if (surface) {
      // Each pass's storage writes are complete before the next pass reads them
      // (continue_pass_'s dependency).
      for (const FluidPass pass : {FluidPass::smooth, FluidPass::smooth_again, FluidPass::shade}) {
        cmd.endRenderPass();
        begin_pass(*continue_pass_);
        draw_fluid(cmd, *f.params, pass);
      }
    }
    draw_lines(cmd, f.view->box, *f.params, true);
  }
  cmd.setViewport(0, ::vk::Viewport(0, 0, float(width()), float(height()), 0, 1));
  cmd.setScissor(0, ::vk::Rect2D({0, 0}, {width(), height()}));
  draw_ui(cmd, f.ui);
  cmd.endRenderPass();
  if (f.readback) target_->record_readback(cmd);
  if (f.after) f.after(cmd, target_->color_image());
  dev_.submit(f.wait, f.wait_stage, f.signal);
  frame_buffers_.clear();
}

}  // namespace masav::render
