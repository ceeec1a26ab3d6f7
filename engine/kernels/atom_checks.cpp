#include "engine/kernels/atom_checks.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "engine/core/error.h"
#include "engine/kernels/kernel_checks.h"
#include "engine/kernels/volume_math.h"

namespace masav {
namespace {

bool finite3(Vec3f v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}
std::string str3(Vec3f v) {
  return fmt::format("({}, {}, {})", v.x, v.y, v.z);
}

void positive(std::string_view where, std::string_view field, float v) {
  if (!std::isfinite(v) || !(v > 0))
    throw_invalid(where, field, fmt::format("{}", v), "finite and > 0");
}

void in_range(std::string_view where, std::string_view field, double v, double lo, double hi) {
  if (!std::isfinite(v) || v < lo || v > hi)
    throw_invalid(where, field, fmt::format("{}", v), fmt::format("in [{}, {}]", lo, hi));
}

void at_least(std::string_view kernel, std::string_view what, size_t have, uint64_t need) {
  if (have < need)
    throw_invalid(kernel, fmt::format("{} size", what), std::to_string(have),
                  fmt::format("at least {}", need));
}

// x in [0, 1] as the nearest of 65,536 steps (volume::unorm16 reads it back).
uint32_t unorm16(double x) {
  return uint32_t(std::lround(std::clamp(x, 0.0, 1.0) * 65535.0));
}

uint32_t snorm16(double x) {
  return uint32_t(int32_t(std::lround(std::clamp(x, -1.0, 1.0) * 32767.0))) & 0xffffu;
}

// A direction as two snorm16 on the octahedron |x| + |y| + |z| = 1 folded onto its upper half
// (volume::octahedral reads it back, to about 1e-4 rad).
uint32_t octahedral_snorm16(Vec3f d) {
  const double l = std::abs(double(d.x)) + std::abs(double(d.y)) + std::abs(double(d.z));
  double x = d.x / l, y = d.y / l;
  if (d.z < 0) {
    const double fx = (1 - std::abs(y)) * (x < 0 ? -1 : 1);
    y = (1 - std::abs(x)) * (y < 0 ? -1 : 1);
    x = fx;
  }
  return snorm16(x) | snorm16(y) << 16;
}

// What both nebula kernels check; `out` is the per-particle output (illumination or light).
void check_nebula(const NebulaLightParams& p, const Buffer<Real4>& positions,
                  const Buffer<Real>& density, const Buffer<Real>& out, std::string_view kernel) {
  check_grid(p.grid, kernel);
  at_least(kernel, "output", out.size(), p.grid.n);
  if (p.grid.n > positions.size())
    throw_invalid(kernel, "particles", std::to_string(p.grid.n),
                  fmt::format("at most the positions buffer's size {}", positions.size()));
  at_least(kernel, "density", density.size(), grid_cell_count(p.grid));
  if (!finite3(p.nucleus)) throw_invalid(kernel, "nucleus", str3(p.nucleus), "finite");
  if (!finite3(p.viewer)) throw_invalid(kernel, "viewer", str3(p.viewer), "finite");
  in_range(kernel, "source_power_lm", p.source_power_lm, 0, 1e12);
  in_range(kernel, "kappa_a2", p.kappa_a2, 0, 1e9);
  if (!std::isfinite(p.albedo) || !(p.albedo > 0) || p.albedo > 1)
    throw_invalid(kernel, "albedo", fmt::format("{}", p.albedo), "in (0, 1]");
  positive(kernel, "core_radius_a0", p.core_radius_a0);
  if (p.path != OpticalPath::exact && p.path != OpticalPath::midpoint)
    throw_invalid(kernel, "path", std::to_string(uint32_t(p.path)), "exact or midpoint");
  positive(kernel, "step_a0", p.step_a0);
  if (p.path == OpticalPath::midpoint) {
    const double diag = double(p.grid.cell_size) * std::sqrt(double(p.grid.dims.x) * p.grid.dims.x +
                                                             double(p.grid.dims.y) * p.grid.dims.y +
                                                             double(p.grid.dims.z) * p.grid.dims.z);
    if (diag / p.step_a0 > kMaxPathSteps)
      throw_invalid(kernel, "step_a0", fmt::format("{}", p.step_a0),
                    fmt::format("at least {:.4g} (the grid's diagonal / {} steps, the most a "
                                "path takes within a shader invocation's loop budget)",
                                diag / kMaxPathSteps, kMaxPathSteps));
  }
  const uint64_t dsum = uint64_t(p.grid.dims.x) + p.grid.dims.y + p.grid.dims.z;
  if (dsum + 3 > kMaxPathSteps)
    throw_invalid(kernel, "grid dims", std::to_string(dsum), "dims.x + dims.y + dims.z < 60000");
}

}  // namespace

size_t orbital_table_size(const OrbitalSampleParams& p) {
  if (p.placement == OrbitalPlacement::shells)
    return size_t(p.radial_bins) * p.polar_bins * p.azimuth_bins + 1;
  return size_t(p.radial_bins) + 1 + p.polar_bins + 1 + (p.azimuth_bins ? p.azimuth_bins + 1 : 0);
}

void validate(const DeviceApi& dev, const OrbitalSampleParams& p, const Buffer<uint32_t>& tables,
              const Buffer<Real4>& positions) {
  const char* k = "orbital_sample";
  if (p.count > positions.size())
    throw_invalid(k, "particles", std::to_string(p.count),
                  fmt::format("at most the positions buffer's size {}", positions.size()));
  check_fits(dev, ElemKind::real4, p.count, k, "the particle positions");
  if (p.placement != OrbitalPlacement::exact && p.placement != OrbitalPlacement::shells)
    throw_invalid(k, "placement", std::to_string(uint32_t(p.placement)), "exact or shells");
  if (p.radial_bins < 1 || p.polar_bins < 1 || p.radial_bins > (1u << 24) ||
      p.polar_bins > (1u << 24) || p.azimuth_bins > (1u << 24))
    throw_invalid(k, "table bins",
                  fmt::format("{}/{}/{}", p.radial_bins, p.polar_bins, p.azimuth_bins),
                  "each in [1, 2^24] (build the tables with make_orbital_tables)");
  if (p.placement == OrbitalPlacement::shells &&
      (p.azimuth_bins < 1 || uint64_t(p.radial_bins) * p.polar_bins * p.azimuth_bins > (1u << 24)))
    throw_invalid(k, "shell sites",
                  std::to_string(uint64_t(p.radial_bins) * p.polar_bins * p.azimuth_bins),
                  "in [1, 2^24]");
  positive(k, "radial_max_a0", p.radial_max_a0);
  if (p.placement == OrbitalPlacement::exact && p.azimuth_bins &&
      (p.azimuth_periods < 2 || p.azimuth_periods > 256 || p.azimuth_periods % 2))
    throw_invalid(k, "azimuth_periods", std::to_string(p.azimuth_periods),
                  "2|m|: an even number in [2, 256]");
  at_least(k, "tables", tables.size(), orbital_table_size(p));
}

void validate(const DeviceApi&, const CloudDensityParams& p, const Buffer<uint32_t>& start,
              const Buffer<uint32_t>& end, const Buffer<Real>& density) {
  const char* k = "cloud_density";
  check_grid(p.grid, k);
  if (p.particles < 1) throw_invalid(k, "particles", std::to_string(p.particles), "at least 1");
  const uint64_t cells = grid_cell_count(p.grid);
  at_least(k, "cell_start", start.size(), cells);
  at_least(k, "cell_end", end.size(), cells);
  at_least(k, "density", density.size(), cells);
}

void validate(const DeviceApi& dev, const ScatterTableParams& p, const Buffer<Real>& table,
              const Buffer<uint32_t>& hits) {
  const char* k = "scatter_table";
  in_range(k, "rows", p.rows, 1, 1u << 20);
  in_range(k, "bins", p.bins, 2, 1024);
  in_range(k, "photons_per_row", p.photons_per_row, 1, 1u << 24);
  if (uint64_t(p.first_row) + p.rows > (1u << 24))
    throw_invalid(k, "first_row", std::to_string(p.first_row), "first_row + rows <= 2^24");
  positive(k, "tau_step", p.tau_step);
  in_range(k, "g", p.g, -0.999, 0.999);
  in_range(k, "albedo", p.albedo, 0, 1);
  if (!std::isfinite(p.weight_threshold) || p.weight_threshold < 0 || p.weight_threshold >= 1)
    throw_invalid(k, "weight_threshold", fmt::format("{}", p.weight_threshold), "in [0, 1)");
  // Within the loop budget of an invocation (65,535 on lavapipe): each event is one loop
  // iteration plus Philox's ten rounds.
  in_range(k, "max_scatterings", p.max_scatterings, 0, 5000);
  if (p.start != ScatterStart::surface && p.start != ScatterStart::centre)
    throw_invalid(k, "start", std::to_string(uint32_t(p.start)), "surface or centre");
  const double len =
      std::sqrt(double(p.direction.x) * p.direction.x + double(p.direction.y) * p.direction.y +
                double(p.direction.z) * p.direction.z);
  if (!finite3(p.direction) || std::abs(len - 1.0) > 1e-3)
    throw_invalid(k, "direction", str3(p.direction), "a unit vector");
  const uint64_t entries = uint64_t(p.rows) * (p.bins + kScatterExtras);
  at_least(k, "table", table.size(), entries);
  at_least(k, "hits", hits.size(), entries);
  check_fits(dev, ElemKind::u32, entries * 2, k, "the 64-bit weight tallies");
}

void validate(const DeviceApi&, const NebulaLightParams& p, const Buffer<Real4>& positions,
              const Buffer<Real>& density, const Buffer<Real>& illumination) {
  check_nebula(p, positions, density, illumination, "nebula_illuminate");
}

void validate(const DeviceApi&, const NebulaLightParams& p, const Buffer<Real4>& positions,
              const Buffer<Real>& density, const Buffer<Real>& table,
              const Buffer<Real>& illumination, const Buffer<Real>& light) {
  const char* k = "nebula_view";
  check_nebula(p, positions, density, light, k);
  in_range(k, "table_rows", p.table_rows, 1, 1u << 20);
  in_range(k, "table_bins", p.table_bins, 2, 1024);
  positive(k, "table_tau_step", p.table_tau_step);
  at_least(k, "table", table.size(), uint64_t(p.table_rows) * p.table_bins);
  at_least(k, "illumination", illumination.size(), p.grid.n);
}

void validate(const DeviceApi& dev, const VoxelizeParams& p, const Buffer<Real4>& positions,
              const Buffer<Real>& light, const Buffer<Real>& probability,
              const Buffer<Real>& mean_light, const Buffer<Real>& sample) {
  const char* k = "voxelize";
  check_grid(p.grid, k);
  if (p.grid.n < 1) throw_invalid(k, "particles", "0", "at least 1");
  at_least(k, "positions", positions.size(), p.grid.n);
  at_least(k, "light", light.size(), p.grid.n);
  const uint64_t cells = grid_cell_count(p.grid);
  at_least(k, "probability", probability.size(), cells);
  at_least(k, "mean_light", mean_light.size(), cells);
  at_least(k, "sample", sample.size(), cells);
  check_fits(dev, ElemKind::u32, cells * 3, k, "the per-cell tallies");
  in_range(k, "s", p.s, 0, 1);
  in_range(k, "t", p.t, 0, 1);
  in_range(k, "light_to_unit", p.light_to_unit, 0, 1e30);
}

void check_volume(const VolumeDesc& v, std::string_view kernel) {
  for (uint32_t d : {v.dims.x, v.dims.y, v.dims.z})
    if (d < 2 || d > 8192)
      throw_invalid(kernel, "volume dims", fmt::format("{}x{}x{}", v.dims.x, v.dims.y, v.dims.z),
                    "each in [2, 8192]");
  if (!finite3(v.box_min) || !finite3(v.box_max) || !(v.box_max.x > v.box_min.x) ||
      !(v.box_max.y > v.box_min.y) || !(v.box_max.z > v.box_min.z))
    throw_invalid(kernel, "volume box", str3(v.box_min) + " - " + str3(v.box_max),
                  "finite with box_max > box_min on every axis");
  if (!std::isfinite(v.value_min) || !std::isfinite(v.value_max) || !(v.value_max > v.value_min))
    throw_invalid(kernel, "value range", fmt::format("[{}, {}]", v.value_min, v.value_max),
                  "finite with value_max > value_min");
  // The kernels normalise in fp32 by (v - value_min) * (1 / width): an overflowing width
  // (+-FLT_MAX) or a denormal one or reciprocal (which GPUs flush to 0) renders black.
  const float width = v.value_max - v.value_min;
  if (!std::isfinite(width) || !std::isnormal(width) || !std::isnormal(1.0f / width))
    throw_invalid(kernel, "value range", fmt::format("[{}, {}]", v.value_min, v.value_max),
                  "a width fp32 normalises by: value_max - value_min finite and with a normal "
                  "reciprocal (normalise the values to [0, 1] first, as the volume loaders do)");
}

UVec3 brick_dims(const VolumeDesc& v, uint32_t brick) {
  return {(v.dims.x + brick - 1) / brick, (v.dims.y + brick - 1) / brick,
          (v.dims.z + brick - 1) / brick};
}

uint64_t brick_count(const VolumeBrickParams& p) {
  const UVec3 b = brick_dims(p.volume, p.brick);
  return uint64_t(b.x) * b.y * b.z;
}

void validate(const DeviceApi&, const VolumeBrickParams& p, const Buffer<Real>& volume,
              const Buffer<Real4>& tf, const Buffer<Real4>& bricks) {
  const char* k = "volume_bricks";
  check_volume(p.volume, k);
  in_range(k, "brick", p.brick, 2, 16);  // (brick + 1)^3 voxels each
  in_range(k, "tf_size", p.tf_size, 2, 4096);
  at_least(k, "transfer function", tf.size(), p.tf_size);
  const uint64_t voxels = uint64_t(p.volume.dims.x) * p.volume.dims.y * p.volume.dims.z;
  at_least(k, "volume", volume.size(), voxels);
  const UVec3 b = brick_dims(p.volume, p.brick);
  at_least(k, "bricks", bricks.size(), uint64_t(b.x) * b.y * b.z);
}

uint64_t brick_count(const BrickSkipParams& p) {
  return uint64_t(p.bricks.x) * p.bricks.y * p.bricks.z;
}

void validate(const DeviceApi&, const BrickSkipParams& p, const Buffer<Real4>& bricks,
              const Buffer<uint32_t>& distances) {
  const char* k = "volume_brick_skip";
  in_range(k, "bricks.x", p.bricks.x, 1, 1 << 16);
  in_range(k, "bricks.y", p.bricks.y, 1, 1 << 16);
  in_range(k, "bricks.z", p.bricks.z, 1, 1 << 16);
  const uint64_t count = brick_count(p);
  // The body indexes bricks and both passes' distances with 32-bit words.
  if (2 * count > 0xffffffffull)
    throw_invalid(k, "bricks", fmt::format("{} x {} x {}", p.bricks.x, p.bricks.y, p.bricks.z),
                  "at most 2^31 bricks");
  in_range(k, "axis", p.axis, 0, 2);
  in_range(k, "radius", p.radius, 1, kBrickSkipMaxRadius);
  at_least(k, "bricks", bricks.size(), count);
  at_least(k, "distances", distances.size(), 2 * count);
}

RaymarchLayout raymarch_layout(const RaymarchParams& p) {
  const double e[3] = {p.eye.x, p.eye.y, p.eye.z}, t[3] = {p.target.x, p.target.y, p.target.z};
  const double u[3] = {p.up.x, p.up.y, p.up.z};
  double f[3] = {t[0] - e[0], t[1] - e[1], t[2] - e[2]};
  auto norm = [](double* v) {
    const double l = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    for (int i = 0; i < 3; ++i) v[i] /= l;
  };
  norm(f);
  double r[3] = {f[1] * u[2] - f[2] * u[1], f[2] * u[0] - f[0] * u[2], f[0] * u[1] - f[1] * u[0]};
  norm(r);
  const double up[3] = {r[1] * f[2] - r[2] * f[1], r[2] * f[0] - r[0] * f[2],
                        r[0] * f[1] - r[1] * f[0]};
  const double th = std::tan(0.5 * double(p.fov_y_deg) * 3.14159265358979323846 / 180.0);
  const double aspect = double(p.width) / double(p.height);
  auto vec = [](double x, double y, double z) { return Vec3f{float(x), float(y), float(z)}; };
  const VolumeDesc& v = p.volume;
  RaymarchLayout c{};
  c.eye = vec(e[0], e[1], e[2]);
  c.forward = vec(f[0], f[1], f[2]);
  c.right = vec(r[0] * th * aspect, r[1] * th * aspect, r[2] * th * aspect);
  c.up = vec(up[0] * th, up[1] * th, up[2] * th);
  c.step = p.step;
  c.reference_step = p.reference_step;
  c.termination_alpha = p.termination_alpha;
  c.value_min = v.value_min;
  c.value_scale = 1.0f / (v.value_max - v.value_min);
  c.box_min = v.box_min;
  c.box_max = v.box_max;
  c.dims = v.dims;
  c.image_size = p.width | p.height << 16;
  uint32_t flags = (p.skip_empty ? kRaySkipEmpty : 0u) | (p.preintegrate ? kRayPreintegrate : 0u) |
                   (p.mode == Compositing::lerp ? kRayLerp : 0u);
  if (p.clip.enabled) {
    flags |= kRayClip | (p.clip.keep_above ? kRayClipKeepAbove : 0u);
    const double lo[3] = {v.box_min.x, v.box_min.y, v.box_min.z};
    const double hi[3] = {v.box_max.x, v.box_max.y, v.box_max.z};
    const uint32_t a = p.clip.axis;
    c.clip_position = float(lo[a] + double(p.clip.position) * (hi[a] - lo[a]));
  }
  const RaymarchParams::Shading& sh = p.shading;
  if (sh.enabled) {
    flags |= kRayShade | (sh.headlight ? kRayHeadlight : 0u);
    c.shade_ambient_diffuse = unorm16(sh.ambient) | unorm16(sh.diffuse) << 16;
    c.shade_specular = unorm16(sh.specular) | unorm16(sh.shininess / kRayMaxShininess) << 16;
    c.shade_light = octahedral_snorm16(sh.light_dir);
  }
  c.bits = flags | (p.clip.enabled ? p.clip.axis : 0u) << kRayClipAxisShift |
           p.brick << kRayBrickShift | p.tf_size << kRayTfSizeShift;
  return c;
}

uint64_t raymarch_invocations(const RaymarchParams& p) {
  return volume::tiled_pixel_count(p.width, p.height);
}

uint64_t max_ray_segments(const RaymarchParams& p) {
  const double dx = double(p.volume.box_max.x) - p.volume.box_min.x;
  const double dy = double(p.volume.box_max.y) - p.volume.box_min.y;
  const double dz = double(p.volume.box_max.z) - p.volume.box_min.z;
  return uint64_t(std::ceil(std::sqrt(dx * dx + dy * dy + dz * dz) / p.step)) + 1;
}

void validate(const DeviceApi& dev, const RaymarchParams& p, const Buffer<Real>& volume,
              const Buffer<Real4>& tf, const Buffer<Real4>& bricks, const Buffer<Real4>& image,
              const Buffer<Real4>* tf_integral) {
  const char* k = "raymarch";
  check_volume(p.volume, k);
  in_range(k, "width", p.width, 1, 16384);
  in_range(k, "height", p.height, 1, 16384);
  if (!finite3(p.eye) || !finite3(p.target) || !finite3(p.up))
    throw_invalid(k, "camera", str3(p.eye) + " " + str3(p.target) + " " + str3(p.up), "finite");
  const double fx = double(p.target.x) - p.eye.x, fy = double(p.target.y) - p.eye.y,
               fz = double(p.target.z) - p.eye.z;
  const double cx = fy * p.up.z - fz * p.up.y, cy = fz * p.up.x - fx * p.up.z,
               cz = fx * p.up.y - fy * p.up.x;
  if (fx * fx + fy * fy + fz * fz < 1e-20)
    throw_invalid(k, "target", str3(p.target), "different from eye " + str3(p.eye));
  if (cx * cx + cy * cy + cz * cz < 1e-12 * (fx * fx + fy * fy + fz * fz))
    throw_invalid(k, "up", str3(p.up), "not parallel to the view direction");
  in_range(k, "fov_y_deg", p.fov_y_deg, 1, 170);
  positive(k, "step", p.step);
  positive(k, "reference_step", p.reference_step);
  in_range(k, "termination_alpha", p.termination_alpha, 0.5, 1);
  in_range(k, "brick", p.brick, 2, 16);
  in_range(k, "tf_size", p.tf_size, 2, 4096);
  if (p.mode != Compositing::front_to_back && p.mode != Compositing::lerp)
    throw_invalid(k, "mode", std::to_string(uint32_t(p.mode)), "front_to_back or lerp");
  if (p.clip.enabled) {
    in_range(k, "clip axis", p.clip.axis, 0, 2);
    in_range(k, "clip position", p.clip.position, 0, 1);
  }
  if (p.shading.enabled) {
    const RaymarchParams::Shading& sh = p.shading;
    in_range(k, "shading ambient", sh.ambient, 0, 1);
    in_range(k, "shading diffuse", sh.diffuse, 0, 1);
    in_range(k, "shading specular", sh.specular, 0, 1);
    in_range(k, "shading shininess", sh.shininess, 1, kRayMaxShininess);
    const Vec3f l = sh.light_dir;
    if (!sh.headlight && (!finite3(l) || !(std::abs(l.x) + std::abs(l.y) + std::abs(l.z) > 1e-6f)))
      throw_invalid(k, "shading light_dir", str3(l), "finite and not (0, 0, 0)");
  }
  if (p.preintegrate) {
    if (p.mode != Compositing::front_to_back)
      throw_invalid(k, "preintegrate", "on with lerp compositing",
                    "off, or on with front_to_back compositing (the lerp mode has no step)");
    if (!tf_integral || !tf_integral->valid())
      throw_invalid(k, "tf_integral", "none",
                    "the pre-integrated table of the transfer function (preintegrate is on)");
    at_least(k, "tf_integral", tf_integral->size(), uint64_t(kPreintegratedPerEntry) * p.tf_size);
  }
  // Loop iterations of the worst ray: its segments, plus a slab test (3) per skipped brick.
  const UVec3 nb = brick_dims(p.volume, p.brick);
  const uint64_t segs = max_ray_segments(p) + 3ull * (uint64_t(nb.x) + nb.y + nb.z) + 16;
  if (segs > kMaxRaySteps)
    throw_invalid(
        k, "step", fmt::format("{}", p.step),
        fmt::format("large enough for at most {} samples across the box ({} now): a "
                    "shader invocation runs at most {} loop iterations on {}",
                    kMaxRaySteps, segs, dev.caps().max_loop_iterations, dev.caps().device_name));
  at_least(k, "transfer function", tf.size(), p.tf_size);
  at_least(k, "volume", volume.size(),
           uint64_t(p.volume.dims.x) * p.volume.dims.y * p.volume.dims.z);
  at_least(k, "bricks", bricks.size(), uint64_t(nb.x) * nb.y * nb.z);
  at_least(k, "image", image.size(), uint64_t(p.width) * p.height);
}

}  // namespace masav
