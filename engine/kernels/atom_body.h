#pragma once
// The electron cloud's per-element bodies: orbital_sample (one particle), cloud_density (one
// cell), nebula_illuminate and nebula_view (one particle), volume_bricks (one brick) and
// raymarch (one pixel), on the math of orbital_math.h, nebula_math.h and volume_math.h. The
// shaders of the same names are the GLSL twins.
#include "engine/kernels/atom_params.h"
#include "engine/kernels/kernel_body.h"
#include "engine/kernels/nebula_math.h"
#include "engine/kernels/orbital_math.h"
#include "engine/kernels/volume_math.h"

namespace masav {

template <>
struct KernelBody<KernelId::orbital_sample> {
  static constexpr uint32_t kCpuGrain = 4096;
  template <class F, class Diag>
  MASAV_HD static void run(uint32_t i, const OrbitalSampleParams& p, Diag&, const uint32_t* tables,
                           hd::V4<F>* positions) {
    const hd::V3<F> x = orbital::sample_particle<F>(p, tables, i);
    positions[i] = hd::V4<F>{x.x, x.y, x.z, F(0)};
  }
};

template <>
struct KernelBody<KernelId::cloud_density> {
  static constexpr uint32_t kCpuGrain = 8192;
  // density[c] = (cell_end[c] - cell_start[c]) / (particles * cell^3).
  template <class F, class Diag>
  MASAV_HD static void run(uint32_t c, const CloudDensityParams& p, Diag&,
                           const uint32_t* cell_start, const uint32_t* cell_end, F* density) {
    const F cell = F(p.grid.cell_size);
    const F scale = F(1) / (F(p.particles) * cell * cell * cell);
    density[c] = F(cell_end[c] - cell_start[c]) * scale;
  }
};

template <>
struct KernelBody<KernelId::nebula_illuminate> {
  static constexpr uint32_t kCpuGrain = 256;
  template <class F, class Diag>
  MASAV_HD static void run(uint32_t i, const NebulaLightParams& p, Diag&,
                           const hd::V4<F>* positions, const F* density, F* illumination) {
    auto at = [density](uint32_t id) { return density[id]; };
    const hd::V4<F> x = positions[i];
    illumination[i] = nebula::illumination<F>(p, hd::V3<F>{x.x, x.y, x.z}, at);
  }
};

template <>
struct KernelBody<KernelId::nebula_view> {
  static constexpr uint32_t kCpuGrain = 256;
  template <class F, class Diag>
  MASAV_HD static void run(uint32_t i, const NebulaLightParams& p, Diag&,
                           const hd::V4<F>* positions, const F* density, const F* table,
                           const F* illumination, F* light) {
    auto dat = [density](uint32_t id) { return density[id]; };
    auto tat = [table](uint32_t k) { return table[k]; };
    const hd::V4<F> x = positions[i];
    light[i] = nebula::view_light<F>(p, hd::V3<F>{x.x, x.y, x.z}, illumination[i], dat, tat);
  }
};

template <>
struct KernelBody<KernelId::volume_bricks> {
  static constexpr uint32_t kCpuGrain = 16;
  // bricks[id] = (value min, value max, largest transfer alpha over that range, 0) over brick id's
  // voxels and the one-voxel apron trilinear sampling reads.
  template <class F, class Diag>
  MASAV_HD static void run(uint32_t id, const VolumeBrickParams& p, Diag&, const F* volume,
                           const hd::V4<F>* tf, hd::V4<F>* bricks) {
    const uint32_t b = p.brick, dx = p.volume.dims.x, dy = p.volume.dims.y, dz = p.volume.dims.z;
    const uint32_t nx = (dx + b - 1) / b, ny = (dy + b - 1) / b;
    const uint32_t bx = id % nx, by = id / nx % ny, bz = id / (nx * ny);
    F lo = F(3.0e38), hi = F(-3.0e38);
    for (uint32_t k = bz * b; k <= hd::min_t((bz + 1) * b, dz - 1); ++k)
      for (uint32_t j = by * b; j <= hd::min_t((by + 1) * b, dy - 1); ++j)
        for (uint32_t i = bx * b; i <= hd::min_t((bx + 1) * b, dx - 1); ++i) {
          const F v = volume[(size_t(k) * dy + j) * dx + i];
          lo = hd::min_t(lo, v);
          hi = hd::max_t(hi, v);
        }
    // Largest alpha of the entries whose linear pieces cover [lo, hi] after normalisation.
    const F vmin = F(p.volume.value_min);
    const F scale = F(1) / (F(p.volume.value_max) - vmin);
    const F nlo = hd::clamp_t((lo - vmin) * scale, F(0), F(1));
    const F nhi = hd::clamp_t((hi - vmin) * scale, F(0), F(1));
    const uint32_t last = p.tf_size - 1;
    const uint32_t k0 = uint32_t(nlo * F(last));
    const uint32_t k1 = hd::min_t(uint32_t(hd::ceil_t(nhi * F(last))), last);
    F amax = F(0);
    for (uint32_t k = k0; k <= k1; ++k) amax = hd::max_t(amax, tf[k].w);
    bricks[id] = hd::V4<F>{lo, hi, amax, F(0)};
  }
};

template <>
struct KernelBody<KernelId::raymarch> {
  static constexpr uint32_t kCpuGrain = 256;
  // image[px] = the composited RGBA (colour premultiplied) of pixel px, row-major from the top.
  template <class F, class Diag>
  MASAV_HD static void run(uint32_t px, const RaymarchLayout& c, Diag&, const F* volume,
                           const hd::V4<F>* tf, const hd::V4<F>* bricks, hd::V4<F>* image) {
    const uint32_t dx = c.dims.x, dy = c.dims.y;
    const uint32_t nbx = (dx + c.brick - 1) / c.brick, nby = (dy + c.brick - 1) / c.brick;
    auto vat = [volume, dx, dy](uint32_t i, uint32_t j, uint32_t k) {
      return volume[(size_t(k) * dy + j) * dx + i];
    };
    auto tat = [tf](uint32_t k) { return volume::V4<F>{tf[k].x, tf[k].y, tf[k].z, tf[k].w}; };
    auto bat = [bricks, nbx, nby](uint32_t x, uint32_t y, uint32_t z) {
      return bricks[(size_t(z) * nby + y) * nbx + x].z;
    };
    const volume::V4<F> o = volume::raymarch_pixel<F>(c, px % c.width, px / c.width, vat, tat, bat);
    image[px] = hd::V4<F>{o.r, o.g, o.b, o.a};
  }
};

}  // namespace masav
