#include <fmt/format.h>

#include <cmath>

#include "engine/atom/atom_scene.h"
#include "engine/core/error.h"
#include "engine/io/png_writer.h"
#include "engine/volume/transfer_function.h"
#include "masav/image.h"
#include "masav/volume.h"

namespace masav {
namespace {

std::vector<Vec4d> checked_transfer(const std::vector<Vec4d>& tf) {
  if (tf.empty()) return volume::resample_transfer(volume::default_transfer_points());
  if (tf.size() < 2 || tf.size() > 4096)
    throw_invalid("masav::raymarch", "transfer", fmt::format("{} entries", tf.size()),
                  "from 2 to 4096 entries");
  for (size_t i = 0; i < tf.size(); ++i)
    for (double c : {tf[i].x, tf[i].y, tf[i].z, tf[i].w})
      if (!(c >= 0 && c <= 1))
        throw_invalid("masav::raymarch", fmt::format("transfer[{}]", i), fmt::format("{}", c),
                      "RGBA values in [0, 1]");
  return tf;
}

}  // namespace

volume::ScalarVolume read_volume(const volume::VolumeFileOptions& options) {
  return volume::load_volume_file(options);
}

volume::ScalarVolume read_volume(const std::string& path) {
  volume::VolumeFileOptions o;
  o.file = path;
  return volume::load_volume_file(o);
}

namespace {

constexpr const char* kWhere = "masav::raymarch";

void check_image_size(uint32_t width, uint32_t height) {
  if (width < 1 || width > 16384 || height < 1 || height > 16384)
    throw_invalid(kWhere, "width x height", fmt::format("{}x{}", width, height),
                  "from 1 to 16384 pixels each");
}

void check_volume(const volume::ScalarVolume& vol) {
  const size_t voxels = size_t(vol.dims.x) * vol.dims.y * vol.dims.z;
  if (vol.dims.x < 2 || vol.dims.y < 2 || vol.dims.z < 2 || vol.values.size() != voxels)
    throw_invalid(kWhere, "volume",
                  fmt::format("{}x{}x{} with {} values", vol.dims.x, vol.dims.y, vol.dims.z,
                              vol.values.size()),
                  "at least 2 samples per axis and one value per voxel");
}

}  // namespace

Image raymarch(Backend& backend, const volume::ScalarVolume& vol, const RaymarchOptions& o) {
  check_image_size(o.width, o.height);
  if (!(o.step_voxels > 0) || o.step_voxels > 16)
    throw_invalid(kWhere, "step_voxels", fmt::format("{}", o.step_voxels), "in (0, 16]");
  check_volume(vol);
  RaymarchParams rp = atom::default_raymarch(volume::volume_desc(vol), atom::parse_view(o.view),
                                             o.width, o.height);
  rp.step *= 2.0f * o.step_voxels;  // default_raymarch steps half a voxel
  rp.mode = o.lerp ? Compositing::lerp : Compositing::front_to_back;
  rp.preintegrate = o.preintegrate;
  return raymarch(backend, vol, rp, o.transfer);
}

Image raymarch(Backend& backend, const volume::ScalarVolume& vol, RaymarchParams rp,
               const std::vector<Vec4d>& transfer) {
  check_image_size(rp.width, rp.height);
  if (!(rp.step > 0) || !std::isfinite(rp.step))
    throw_invalid(kWhere, "step", fmt::format("{}", rp.step), "a positive length");
  check_volume(vol);
  const std::vector<Vec4d> tf = checked_transfer(transfer);
  rp.volume = volume::volume_desc(vol);
  auto buffer = backend.create<Real>(vol.values.size(), "masav::raymarch volume");
  backend.upload(buffer, std::span<const float>(vol.values));
  return {rp.width, rp.height, atom::render_volume(backend, rp.volume, buffer, tf, rp)};
}

void save_png(const std::string& path, const Image& image) {
  if (image.pixels.size() != size_t(image.width) * image.height || image.pixels.empty())
    throw_invalid("masav::save_png", "image",
                  fmt::format("{}x{} with {} pixels", image.width, image.height,
                              image.pixels.size()),
                  "width * height pixels, at least one");
  write_png(path, image.width, image.height, to_rgba8(image.pixels));
}

}  // namespace masav
