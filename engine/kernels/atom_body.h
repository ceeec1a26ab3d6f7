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
  // bricks[id] = (value min, value max, largest transfer alpha over that range, 1) over the voxels
  // and the one-voxel apron that trilinear sampling reads there. The 1 is the stride a ray may
  // cross the brick in, in bricks: this brick alone, until volume_brick_skip widens it.
  template <class F, class Diag>
  MASAV_HD static void run(uint32_t id, const VolumeBrickParams& p, Diag&, const F* volume,
                           const hd::V4<F>* tf, hd::V4<F>* bricks) {
    const uint32_t b = p.brick;
    const uint32_t d[3] = {p.volume.dims.x, p.volume.dims.y, p.volume.dims.z};
    const uint32_t nx = (d[0] + b - 1) / b, ny = (d[1] + b - 1) / b;
    const uint32_t bi[3] = {id % nx, id / nx % ny, id / (nx * ny)};
    uint32_t first[3], last[3];
    for (int a = 0; a < 3; ++a) {
      first[a] = bi[a] * b;
      last[a] = hd::min_t((bi[a] + 1) * b, d[a] - 1);
    }
    F lo, hi;
    value_range(volume, d, first, last, lo, hi);
    bricks[id] = hd::V4<F>{lo, hi, range_alpha(p, tf, lo, hi), F(1)};
  }

 private:
  template <class F>
  MASAV_HD static void value_range(const F* volume, const uint32_t d[3], const uint32_t first[3],
                                   const uint32_t last[3], F& lo, F& hi) {
    lo = F(3.0e38);
    hi = F(-3.0e38);
    for (uint32_t k = first[2]; k <= last[2]; ++k)
      for (uint32_t j = first[1]; j <= last[1]; ++j)
        for (uint32_t i = first[0]; i <= last[0]; ++i) {
          const F v = volume[(size_t(k) * d[1] + j) * d[0] + i];
          lo = hd::min_t(lo, v);
          hi = hd::max_t(hi, v);
        }
  }
  // Largest alpha of the entries whose linear pieces cover [lo, hi] after normalisation.
  template <class F>
  MASAV_HD static F range_alpha(const VolumeBrickParams& p, const hd::V4<F>* tf, F lo, F hi) {
    const F vmin = F(p.volume.value_min);
    const F scale = F(1) / (F(p.volume.value_max) - vmin);
    const F nlo = hd::clamp_t((lo - vmin) * scale, F(0), F(1));
    const F nhi = hd::clamp_t((hi - vmin) * scale, F(0), F(1));
    const uint32_t last = p.tf_size - 1;
    const uint32_t k0 = uint32_t(nlo * F(last));
    const uint32_t k1 = hd::min_t(uint32_t(hd::ceil_t(nhi * F(last))), last);
    F amax = F(0);
    for (uint32_t k = k0; k <= k1; ++k) amax = hd::max_t(amax, tf[k].w);
    return amax;
  }
};

template <>
struct KernelBody<KernelId::volume_brick_skip> {
  static constexpr uint32_t kCpuGrain = 1024;
  // One pass of the separable max-norm distance transform over the brick grid (x fastest), both
  // ways at once: the distance to the nearest occupied brick (low 16 bits of a word) and to the
  // nearest empty one (high 16), each at most radius + 1. Pass 0 reads the bricks' alpha along x
  // and writes distances[id]; pass 1 reads those along y and writes distances[count + id]; pass 2
  // reads those along z and writes the distance to the other kind to bricks[id].w. The minimum
  // over the line of max(|offset|, the previous pass's distance there) is the distance over the
  // line's neighbourhood, since max(|dx|, |dy|, |dz|) nests.
  template <class F, class Diag>
  MASAV_HD static void run(uint32_t id, const BrickSkipParams& p, Diag&, hd::V4<F>* bricks,
                           uint32_t* distances) {
    const uint32_t n[3] = {p.bricks.x, p.bricks.y, p.bricks.z};
    const uint32_t count = n[0] * n[1] * n[2];
    const uint32_t a = p.axis;
    const uint32_t at = a == 0u ? id % n[0] : (a == 1u ? id / n[0] % n[1] : id / (n[0] * n[1]));
    const uint32_t stride = a == 0u ? 1u : (a == 1u ? n[0] : n[0] * n[1]);
    const uint32_t line = id - at * stride;  // the line's first brick
    const uint32_t far = p.radius + 1u;
    const uint32_t first = at > p.radius ? at - p.radius : 0u;
    const uint32_t last = hd::min_t(at + p.radius, n[a] - 1u);
    uint32_t to_occupied = far, to_empty = far;
    for (uint32_t c = first; c <= last; ++c) {
      const uint32_t j = line + c * stride;
      const uint32_t off = c > at ? c - at : at - c;
      uint32_t occupied, empty;
      if (a == 0u) {
        const bool o = bricks[j].z > F(0);
        occupied = o ? 0u : far;
        empty = o ? far : 0u;
      } else {
        const uint32_t w = distances[(a - 1u) * count + j];
        occupied = w & 0xffffu;
        empty = w >> 16;
      }
      to_occupied = hd::min_t(to_occupied, hd::max_t(off, occupied));
      to_empty = hd::min_t(to_empty, hd::max_t(off, empty));
    }
    if (a < 2u)
      distances[a * count + id] = to_occupied | (to_empty << 16);
    else
      bricks[id].w = F(bricks[id].z > F(0) ? to_empty : to_occupied);
  }
};

template <>
struct KernelBody<KernelId::raymarch> {
  static constexpr uint32_t kCpuGrain = 256;
  // CUDA: three blocks of 256 per multiprocessor. Unbounded the kernel takes 140 registers (one
  // block, 12.5% occupancy); bounded (80, some spilled to L1) it ran an H100's 60^3 at 1024^2 in
  // 0.82 ms against 1.38 and 256^3 at 1920x1080 in 4.98 against 8.82 (two blocks: 0.87, 5.45).
  static constexpr int kCudaMinBlocks = 3;
  // Invocation id marches the pixel volume::tile_pixel gives (8x8 tiles); image[y * width + x]
  // = its composited RGBA (colour premultiplied), rows from the top. tf_integral: the
  // pre-integrated table (volume::segment_mean), read when c.bits has kRayPreintegrate.
  template <class F, class Diag>
  MASAV_HD static void run(uint32_t id, const RaymarchLayout& c, Diag&, const F* volume,
                           const hd::V4<F>* tf, const hd::V4<F>* bricks, hd::V4<F>* image,
                           const hd::V4<F>* tf_integral) {
    uint32_t x, y;
    if (!volume::tile_pixel(c, id, x, y)) return;
    const volume::V4<F> o = pixel<F>(c, x, y, volume, tf, bricks, tf_integral);
    image[size_t(y) * volume::ray_width(c) + x] = hd::V4<F>{o.r, o.g, o.b, o.a};
  }

  // Pixel (x, y) in precision F from buffers in F (the CPU backend's fp32 render path calls this
  // directly).
  template <class F>
  MASAV_HD static volume::V4<F> pixel(const RaymarchLayout& c, uint32_t x, uint32_t y,
                                      const F* volume, const hd::V4<F>* tf, const hd::V4<F>* bricks,
                                      const hd::V4<F>* tf_integral) {
    const uint32_t dx = c.dims.x, dy = c.dims.y;
    const uint32_t brick = volume::ray_brick(c);
    const uint32_t nbx = (dx + brick - 1) / brick, nby = (dy + brick - 1) / brick;
    auto vat = [volume, dx, dy](uint32_t i, uint32_t j, uint32_t k) {
      return volume[(size_t(k) * dy + j) * dx + i];
    };
    auto occ = [bricks, nbx, nby](uint32_t bx, uint32_t by, uint32_t bz) {
      const hd::V4<F> b = bricks[(size_t(bz) * nby + by) * nbx + bx];
      return volume::Occupancy<F>{b.z, b.w};  // (alpha, stride in bricks)
    };
    auto entry = [](const hd::V4<F>* table) {
      return [table](uint32_t k) {
        return volume::V4<F>{table[k].x, table[k].y, table[k].z, table[k].w};
      };
    };
    if (c.bits & kRayPreintegrate)
      return volume::raymarch_pixel_preintegrated<F>(c, x, y, vat, entry(tf_integral), occ);
    return volume::raymarch_pixel<F>(c, x, y, vat, entry(tf), occ);
  }
};

}  // namespace masav
