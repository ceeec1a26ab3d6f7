#include "engine/volume/volume_render.h"

#include <fmt/format.h>

#include <algorithm>

#include "engine/core/error.h"
#include "engine/kernels/atom_checks.h"
#include "engine/scene/scene.h"
#include "engine/volume/brick_skip.h"
#include "engine/volume/preintegration.h"

namespace masav::volume {

void add_inline_transfer_key(scene::TableSchema& s) {
  s.text("transfer", "",
         "transfer function inline: points 'value r g b a' separated by ';', each number in [0, "
         "1], values ascending (what the demo's editor saves; '' = transfer_file)");
}

void check_transfer_keys(const scene::ParamSet& p, const std::string& table) {
  const std::string key = table + ".transfer";
  const std::string& inline_points = p.get_text(key);
  if (inline_points.empty()) return;
  (void)parse_inline_transfer(inline_points, key);
  const std::string& file = p.get_text(table + ".transfer_file");
  if (!file.empty())
    throw Error("", "scene",
                fmt::format("{} and {}.transfer_file = {} are both set", key, table, file),
                fmt::format("set one of them: clear {}.transfer_file (\"\") to use the inline "
                            "points, or {} to use the file",
                            table, key));
}

std::vector<TransferPoint> transfer_points_of(const scene::ParamSet& p, const std::string& table) {
  check_transfer_keys(p, table);
  const std::string& inline_points = p.get_text(table + ".transfer");
  if (!inline_points.empty()) return parse_inline_transfer(inline_points, table + ".transfer");
  const std::string& file = p.get_text(table + ".transfer_file");
  return file.empty() ? default_transfer_points() : load_transfer_points(file);
}

void VolumeRender::load_transfer(const std::vector<TransferPoint>& points) {
  const std::vector<Vec4d> tf = resample_transfer(points);
  if (tf_.size() != tf.size()) tf_ = backend_.create<Real4>(tf.size(), "transfer function");
  backend_.upload(tf_, tf);
  tf_integral_ = upload_preintegrated(backend_, tf);
  tf_colours_.clear();
  for (const Vec4d& c : tf) tf_colours_.push_back({float(c.x), float(c.y), float(c.z), 1.0f});
}

void VolumeRender::build_bricks(const VolumeDesc& d, const Buffer<Real>& volume) {
  const uint32_t brick = RaymarchParams{}.brick;
  const UVec3 nb = brick_dims(d, brick);
  const size_t n = size_t(nb.x) * nb.y * nb.z;
  if (bricks_.size() != n) bricks_ = backend_.create<Real4>(n, "bricks");
  fill_bricks(backend_, {d, brick, uint32_t(tf_.size())}, volume, tf_, bricks_);
}

void add_clip_shade_keys(scene::TableSchema& s) {
  s.choice("clip", "off", {"off", "x", "y", "z"},
           "clipping plane across this axis: the volume on one side of it is removed");
  s.real("clip_position", 0.5, 0.0, 1.0, "where the clipping plane cuts its axis", "of the box");
  s.steps(0.01);
  s.choice("clip_keep", "above", {"above", "below"},
           "the side of the clipping plane kept: higher or lower coordinates");
  s.flag("shade", false,
         "Blinn-Phong shading from the volume's gradient, lit from the camera (headlight)");
  s.real("shade_specular", 0.3, 0.0, 1.0, "specular weight of the shading");
  s.steps(0.05);
}

void VolumeRender::raymarch(const scene::ParamSet& p, const std::string& table, const VolumeDesc& d,
                            const Buffer<Real>& volume, const scene::CameraPose& c,
                            uint32_t level) {
  RaymarchParams rp;
  rp.volume = d;
  rp.tf_size = uint32_t(tf_.size());
  const uint32_t shrink = 1u << std::min(level, scene::kMaxPreviewLevel);
  rp.width = (uint32_t(p.get_int("render.width")) + shrink - 1) / shrink;
  rp.height = (uint32_t(p.get_int("render.height")) + shrink - 1) / shrink;
  rp.eye = c.eye;
  rp.target = c.target;
  rp.up = c.up;
  rp.fov_y_deg = c.fov_y_deg;
  const float voxel = std::min({(d.box_max.x - d.box_min.x) / float(d.dims.x),
                                (d.box_max.y - d.box_min.y) / float(d.dims.y),
                                (d.box_max.z - d.box_min.z) / float(d.dims.z)});
  rp.step = float(p.get_real(table + ".step_voxels")) * voxel;
  // A preview (the view moving, 1/2^level of the pixels upsampled) samples at least a voxel
  // apart: half the samples at the default 1/2 voxel, the brightness kept by the opacity
  // correction; the still frame (level 0) samples as asked.
  if (shrink > 1) rp.step = std::max(rp.step, voxel);
  rp.reference_step = voxel;
  rp.mode =
      p.get_text(table + ".compositing") == "lerp" ? Compositing::lerp : Compositing::front_to_back;
  rp.preintegrate = p.get_flag(table + ".preintegrate");
  const std::string& clip = p.get_text(table + ".clip");
  rp.clip.enabled = clip != "off";
  rp.clip.axis = clip == "y" ? 1u : (clip == "z" ? 2u : 0u);
  rp.clip.position = float(p.get_real(table + ".clip_position"));
  rp.clip.keep_above = p.get_text(table + ".clip_keep") == "above";
  rp.shading.enabled = p.get_flag(table + ".shade");
  rp.shading.specular = float(p.get_real(table + ".shade_specular"));
  // The buffer of the full image holds every level's: a preview does not reallocate it.
  const size_t pixels = size_t(rp.width) * rp.height;
  if (image_.size() < pixels) image_ = backend_.create<Real4>(pixels, "raymarched image");
  backend_.raymarch(rp, volume, tf_, bricks_, image_, &tf_integral_);
  image_w_ = rp.width;
  image_h_ = rp.height;
}

std::optional<scene::ImageLayer> VolumeRender::image_layer(float gain, std::string key_title,
                                                           float key_lo, float key_hi,
                                                           uint64_t version) const {
  if (!image_.valid() || version == 0) return std::nullopt;
  scene::ImageLayer img;
  img.pixels = &image_.impl();
  img.width = image_w_;
  img.height = image_h_;
  img.format = scene::ImageLayer::Format::rgba32f;
  img.gain = gain;
  img.key = scene::ColourKey{std::move(key_title), key_lo, key_hi, tf_colours_};
  img.version = version;
  return img;
}

}  // namespace masav::volume
