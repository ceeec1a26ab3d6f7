#pragma once
// A scene's raymarched volume: the transfer function's tables, the volume's bricks and the image
// raymarched from the scene's camera. The atom-volume scene (the voxelized cloud) and the volume
// scene (a file) both draw through it, with their raymarch keys in their own table.
#include <optional>
#include <string>
#include <vector>

#include "engine/kernels/backend.h"
#include "engine/scene/camera_pose.h"
#include "engine/scene/param_schema.h"
#include "engine/scene/scene_view.h"
#include "engine/volume/transfer_function.h"

namespace masav::volume {

// The clipping plane's and the shading's keys (clip, clip_position, clip_keep, shade,
// shade_specular) of a table raymarch() reads.
void add_clip_shade_keys(scene::TableSchema& s);

// The key `transfer` of a raymarch table, beside its `transfer_file`: the points inline
// ("value r g b a; ..."), as the demo's transfer function editor keeps them, so a saved scene is
// one file that needs no other. At most one of the two is set.
void add_inline_transfer_key(scene::TableSchema& s);
// The checks of `table`.transfer (the points, read as a file's lines are) and that
// `table`.transfer_file is not set as well; reads no file (for a scene's validate()).
void check_transfer_keys(const scene::ParamSet& p, const std::string& table);
// The points `table`'s keys give: the inline ones, the file's, or the default.
std::vector<TransferPoint> transfer_points_of(const scene::ParamSet& p, const std::string& table);

class VolumeRender {
 public:
  explicit VolumeRender(Backend& b) : backend_(b) {}

  // The transfer function's table (resampled from `points`), its pre-integrated table, and the
  // colours of its colour bar.
  void load_transfer(const std::vector<TransferPoint>& points);
  // The bricks' value ranges for empty-space skipping (after load_transfer).
  void build_bricks(const VolumeDesc& d, const Buffer<Real>& volume);
  // Raymarches at render.width x render.height from the camera pose, with `table`.step_voxels,
  // .compositing, .preintegrate and the clip and shade keys (after build_bricks). At preview
  // level L the image is 1/2^L of that size per axis (rounded up), the same rays otherwise.
  void raymarch(const scene::ParamSet& p, const std::string& table, const VolumeDesc& d,
                const Buffer<Real>& volume, const scene::CameraPose& c, uint32_t level = 0);

  // The last image, as the scene's background with a colour bar of the transfer function from
  // key_lo to key_hi; none before the first raymarch.
  std::optional<scene::ImageLayer> image_layer(float gain, std::string key_title, float key_lo,
                                               float key_hi, uint64_t version) const;

 private:
  Backend& backend_;
  Buffer<Real4> tf_, tf_integral_, bricks_, image_;
  std::vector<Vec4f> tf_colours_;
  uint32_t image_w_ = 0, image_h_ = 0;
};

}  // namespace masav::volume
