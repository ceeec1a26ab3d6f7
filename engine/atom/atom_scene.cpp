#include "engine/atom/atom_scene.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>

#include "engine/core/error.h"
#include "engine/grid/hash_grid.h"
#include "engine/kernels/atom_checks.h"
#include "engine/volume/brick_skip.h"
#include "engine/volume/preintegration.h"

namespace masav::atom {

Vec3f full_colour_viewer(double box_half_width) {
  return view_eye(ViewPreset::front, float(1.9 * box_half_width * std::sqrt(3.0)));
}

ViewPreset parse_view(const std::string& name) {
  if (name == "top") return ViewPreset::top;
  if (name == "left") return ViewPreset::left;
  if (name == "front") return ViewPreset::front;
  throw_invalid("atom", "view", name, "top, left or front");
}

Vec3f view_eye(ViewPreset v, float d) {
  switch (v) {
    case ViewPreset::top:
      return {0, 0, d};
    case ViewPreset::left:
      return {-d, 0, 0};
    case ViewPreset::front:
      return {0, -d, 0};
  }
  return {0, -d, 0};
}

Vec3f view_up(ViewPreset v) {
  return v == ViewPreset::top ? Vec3f{0, 1, 0} : Vec3f{0, 0, 1};
}

AtomScene::AtomScene(Backend& b, AtomSceneOptions o) : b_(b) {
  reconfigure(std::move(o));
}

void AtomScene::reconfigure(AtomSceneOptions o) {
  o_ = std::move(o);
  validate_state(o_.state, "atom");
  if (o_.particles < 1)
    throw_invalid("atom", "particles", std::to_string(o_.particles), "at least 1");
  const uint64_t limit = b_.caps().max_buffer_bytes;
  if (limit && uint64_t(o_.particles) * 4 * b_.real_bytes() > limit)
    throw_invalid("atom", "particles", std::to_string(o_.particles),
                  fmt::format("at most {} on {} (one buffer holds {} MiB)",
                              limit / (4 * b_.real_bytes()), b_.caps().device_name, limit >> 20));
  for (auto [name, v] :
       {std::pair{"density_dims", o_.density_dims}, {"volume_dims", o_.volume_dims}})
    if (v < 2 || v > 512) throw_invalid("atom", name, std::to_string(v), "in [2, 512]");
  if (!(o_.box_probability >= 0.9 && o_.box_probability < 1 - 1e-9))
    throw_invalid("atom", "box_probability", fmt::format("{}", o_.box_probability), "in [0.9, 1)");
  if (!std::isfinite(o_.tau_peak) || o_.tau_peak < 0)
    throw_invalid("atom", "tau_peak", fmt::format("{}", o_.tau_peak), "finite and >= 0");
  half_ = atom::box_half_width(o_.state, o_.box_probability);
  const float h = float(half_);
  density_grid_ =
      make_grid_params({-h, -h, -h}, 2 * h / float(o_.density_dims),
                       {o_.density_dims, o_.density_dims, o_.density_dims}, o_.particles);
  volume_grid_ = make_grid_params({-h, -h, -h}, 2 * h / float(o_.volume_dims),
                                  {o_.volume_dims, o_.volume_dims, o_.volume_dims}, o_.particles);
  // sigma_sct = kappa * density: tau_peak at the state's largest |psi|^2 over one cell.
  kappa_ = float(o_.tau_peak / (peak_density(o_.state) * density_grid_.cell_size));
  if (o_.viewer.x == 0 && o_.viewer.y == 0 && o_.viewer.z == 0)
    o_.viewer = view_eye(ViewPreset::front, 2.5f * h);
}

double AtomScene::timed(const std::function<void()>& work) {
  b_.finish();
  const auto t0 = std::chrono::steady_clock::now();
  work();
  b_.finish();
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

void AtomScene::build_cloud() {
  tables_ = make_orbital_tables(o_.state, o_.placement, o_.particles, o_.seed, o_.tables);
  auto cdf = b_.create<uint32_t>(tables_.cdf.size(), "orbital tables");
  b_.upload(cdf, tables_.cdf);
  positions = b_.create<Real4>(o_.particles, "cloud positions");
  times_.cloud_ms = timed([&] { b_.orbital_sample(tables_.params, cdf, positions); });
}

void AtomScene::build_density() {
  density = b_.create<Real>(grid_cell_count(density_grid_), "cloud density");
  times_.density_ms = timed([&] {
    HashGrid g = make_hash_grid(b_, density_grid_, o_.particles);
    build_hash_grid(b_, g, positions);
    b_.cloud_density({density_grid_, o_.particles}, g.cell_start, g.cell_end, density);
    b_.finish();  // the grid's buffers die here
  });
}

void AtomScene::build_table() {
  full_colour_ = 0;  // a new phase table
  const auto t0 = std::chrono::steady_clock::now();
  if (o_.use_cache) {
    table_ = scatter_table_cached(b_, o_.scatter, o_.cache_dir, &times_.table_from_cache);
  } else {
    table_ = compute_scatter_table(b_, o_.scatter);
    times_.table_from_cache = false;
  }
  const std::vector<double> ph = make_phase_table(table_);
  phase = b_.create<Real>(ph.size(), "phase table");
  b_.upload(phase, ph);
  times_.table_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

NebulaLightParams AtomScene::light_params() const {
  NebulaLightParams p;
  p.grid = density_grid_;
  p.source_power_lm = o_.source_power_lm;
  p.kappa_a2 = kappa_;
  p.albedo = o_.scatter.albedo > 0 ? o_.scatter.albedo : 1.0f;
  p.core_radius_a0 = 0.5f * density_grid_.cell_size;
  p.viewer = o_.viewer;
  p.path = o_.path;
  p.step_a0 = o_.step_a0 > 0 ? o_.step_a0 : 0.5f * density_grid_.cell_size;
  p.table_rows = o_.scatter.rows;
  p.table_bins = o_.scatter.bins;
  p.table_tau_step = o_.scatter.tau_step;
  return p;
}

void AtomScene::illuminate() {
  full_colour_ = 0;  // a new light field
  if (illumination.size() != o_.particles)
    illumination = b_.create<Real>(o_.particles, "illumination");
  times_.illuminate_ms =
      timed([&] { b_.nebula_illuminate(light_params(), positions, density, illumination); });
}

void AtomScene::view() {
  if (light.size() != o_.particles) light = b_.create<Real>(o_.particles, "light");
  times_.view_ms = timed(
      [&] { b_.nebula_view(light_params(), positions, density, phase, illumination, light); });
}

float AtomScene::exposure() {
  return o_.exposure > 0 ? o_.exposure : float(1.0 / full_colour_light());
}

double AtomScene::full_colour_light() {
  if (full_colour_ > 0) return full_colour_;
  const Vec3f front = full_colour_viewer(half_);
  std::vector<double> l;
  if (o_.viewer.x == front.x && o_.viewer.y == front.y && o_.viewer.z == front.z) {
    l = b_.download(light);
  } else {
    NebulaLightParams p = light_params();
    p.viewer = front;
    Buffer<Real> seen = b_.create<Real>(o_.particles, "light from the front");
    b_.nebula_view(p, positions, density, phase, illumination, seen);
    l = b_.download(seen);
  }
  const size_t k = l.size() * 9 / 10;
  std::nth_element(l.begin(), l.begin() + std::ptrdiff_t(k), l.end());
  // At the reference power: a change of Phi brightens or darkens, as in the thesis.
  const double ref = l[k] * kReferencePowerLm / std::max(1e-30, double(o_.source_power_lm));
  full_colour_ = ref > 0 ? ref : 1.0;
  return full_colour_;
}

void AtomScene::voxelize() {
  voxelize(exposure());
}

void AtomScene::voxelize(float light_to_unit) {
  const size_t cells = grid_cell_count(volume_grid_);
  if (sample.size() != cells) {
    probability = b_.create<Real>(cells, "p");
    mean_light = b_.create<Real>(cells, "g");
    sample = b_.create<Real>(cells, "sample");
  }
  VoxelizeParams vp;
  vp.grid = volume_grid_;
  vp.s = o_.s;
  vp.t = o_.t;
  vp.light_to_unit = light_to_unit;
  times_.voxelize_ms =
      timed([&] { b_.voxelize(vp, positions, light, probability, mean_light, sample); });
}

void AtomScene::run_all() {
  build_cloud();
  build_density();
  build_table();
  illuminate();
  view();
  voxelize();
}

VolumeDesc AtomScene::volume() const {
  const float h = float(half_);
  return make_volume_desc(volume_grid_.dims, {-h, -h, -h}, {h, h, h});
}

RaymarchParams default_raymarch(const VolumeDesc& d, ViewPreset view, uint32_t width,
                                uint32_t height) {
  RaymarchParams rp;
  rp.volume = d;
  rp.width = width;
  rp.height = height;
  const Vec3f c{0.5f * (d.box_min.x + d.box_max.x), 0.5f * (d.box_min.y + d.box_max.y),
                0.5f * (d.box_min.z + d.box_max.z)};
  const float ex = d.box_max.x - d.box_min.x, ey = d.box_max.y - d.box_min.y,
              ez = d.box_max.z - d.box_min.z;
  const float half_diag = 0.5f * std::sqrt(ex * ex + ey * ey + ez * ez);
  const Vec3f e = view_eye(view, 1.9f * half_diag);
  rp.eye = {c.x + e.x, c.y + e.y, c.z + e.z};
  rp.target = c;
  rp.up = view_up(view);
  rp.fov_y_deg = 45.0f;
  const float voxel = std::min({ex / d.dims.x, ey / d.dims.y, ez / d.dims.z});
  rp.step = 0.5f * voxel;
  rp.reference_step = voxel;
  rp.tf_size = 256;
  return rp;
}

RaymarchBuffers prepare_raymarch(Backend& b, const Buffer<Real>& volume,
                                 const std::vector<Vec4d>& tf, const RaymarchParams& rp) {
  RaymarchBuffers r;
  r.tf = b.create<Real4>(tf.size(), "transfer function");
  b.upload(r.tf, tf);
  const UVec3 nb = brick_dims(rp.volume, rp.brick);
  r.bricks = b.create<Real4>(size_t(nb.x) * nb.y * nb.z, "bricks");
  volume::fill_bricks(b, {rp.volume, rp.brick, rp.tf_size}, volume, r.tf, r.bricks);
  if (rp.preintegrate) r.tf_integral = volume::upload_preintegrated(b, tf);
  r.image = b.create<Real4>(size_t(rp.width) * rp.height, "image");
  return r;
}

void raymarch_frame(Backend& b, const RaymarchParams& rp, const Buffer<Real>& volume,
                    RaymarchBuffers& r) {
  b.raymarch(rp, volume, r.tf, r.bricks, r.image, r.tf_integral.valid() ? &r.tf_integral : nullptr);
}

std::vector<Vec4d> render_volume(Backend& b, const VolumeDesc& desc, const Buffer<Real>& volume,
                                 const std::vector<Vec4d>& tf, RaymarchParams rp) {
  rp.volume = desc;
  rp.tf_size = uint32_t(tf.size());
  RaymarchBuffers r = prepare_raymarch(b, volume, tf, rp);
  raymarch_frame(b, rp, volume, r);
  return b.download(r.image);
}

}  // namespace masav::atom
