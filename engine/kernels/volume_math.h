#pragma once
// Volume ray casting (thesis chapter 3), shared by the CPU reference (T = double) and CUDA
// (T = float); shaders/common/volume.glsl is the GLSL twin: the slab ray-box test (thesis
// Alg. 3.1), trilinear sampling, the 1-D transfer function, and one pixel's march.
//
// Sampling: the ray's span inside the box [t_near, t_far] is cut into n = ceil(len / step)
// segments of length `step` (the last shorter); each is sampled at its midpoint. Front-to-back
// emission-absorption with the opacity of a segment of length h corrected from the transfer
// function's reference step: alpha_h = 1 - (1 - alpha)^(h / reference_step), so the image does
// not depend on the step beyond the quadrature error. For a smooth field the composited opacity
// is the midpoint rule for 1 - exp(-int kappa ds): error O(step^2) (tests: test_raymarch.cpp).
#include <cstdint>

#include "engine/kernels/atom_params.h"
#include "engine/kernels/hd_vec.h"

namespace masav::volume {

constexpr float kFar = 1e30f;

template <class T>
struct V4 {
  T r, g, b, a;
};

// Kay-Kajiya slabs: clips [t_near, t_far] to the box; false when the ray misses it (or the
// clipped span is empty). A zero direction component needs the origin inside that slab.
template <class T>
MASAV_HD inline bool slab(hd::V3<T> o, hd::V3<T> d, hd::V3<T> lo, hd::V3<T> hi, T& t_near,
                          T& t_far) {
  for (int a = 0; a < 3; ++a) {
    const T oa = hd::comp(o, a), da = hd::comp(d, a), la = hd::comp(lo, a), ha = hd::comp(hi, a);
    if (da == T(0)) {
      if (oa < la || oa > ha) return false;
      continue;
    }
    T t1 = (la - oa) / da, t2 = (ha - oa) / da;
    if (t1 > t2) {
      const T s = t1;
      t1 = t2;
      t2 = s;
    }
    if (t1 > t_near) t_near = t1;
    if (t2 < t_far) t_far = t2;
    if (t_near > t_far) return false;
  }
  return true;
}

// Trilinear interpolation at voxel coordinates u (voxel centres at integers), clamped to the
// outermost centres. at(i, j, k) returns the voxel value.
template <class T, class At>
MASAV_HD inline T trilinear(hd::V3<T> u, const uint32_t dims[3], At&& at) {
  uint32_t i0[3], i1[3];
  T f[3];
  for (int a = 0; a < 3; ++a) {
    const T hi = T(dims[a] - 1u);
    const T c = hd::clamp_t(hd::comp(u, a), T(0), hi);
    i0[a] = uint32_t(c);  // c >= 0: truncation is the floor, without a libm call
    const T fl = T(i0[a]);
    i1[a] = i0[a] + 1u < dims[a] ? i0[a] + 1u : i0[a];
    f[a] = c - fl;
  }
  const T c00 = at(i0[0], i0[1], i0[2]) * (T(1) - f[0]) + at(i1[0], i0[1], i0[2]) * f[0];
  const T c10 = at(i0[0], i1[1], i0[2]) * (T(1) - f[0]) + at(i1[0], i1[1], i0[2]) * f[0];
  const T c01 = at(i0[0], i0[1], i1[2]) * (T(1) - f[0]) + at(i1[0], i0[1], i1[2]) * f[0];
  const T c11 = at(i0[0], i1[1], i1[2]) * (T(1) - f[0]) + at(i1[0], i1[1], i1[2]) * f[0];
  const T c0 = c00 * (T(1) - f[1]) + c10 * f[1];
  const T c1 = c01 * (T(1) - f[1]) + c11 * f[1];
  return c0 * (T(1) - f[2]) + c1 * f[2];
}

// Transfer function: `size` RGBA entries over [0, 1], linear between entries. tf(k) returns entry
// k.
template <class T, class Tf>
MASAV_HD inline V4<T> transfer(T v, uint32_t size, Tf&& tf) {
  const T x = hd::clamp_t(v, T(0), T(1)) * T(size - 1u);
  uint32_t k = uint32_t(x);
  if (k > size - 2u) k = size - 2u;
  const T w = x - T(k);
  const V4<T> a = tf(k), b = tf(k + 1u);
  return V4<T>{a.r + (b.r - a.r) * w, a.g + (b.g - a.g) * w, a.b + (b.b - a.b) * w,
               a.a + (b.a - a.a) * w};
}

// What every pixel derives from the layout, in float as the host would: voxel spacing and the
// brick grid.
struct RayGeometry {
  float spacing[3];
  uint32_t bricks[3];
};

MASAV_HD inline RayGeometry ray_geometry(const RaymarchLayout& c) {
  RayGeometry g{};
  const float lo[3] = {c.box_min.x, c.box_min.y, c.box_min.z};
  const float hi[3] = {c.box_max.x, c.box_max.y, c.box_max.z};
  const uint32_t dims[3] = {c.dims.x, c.dims.y, c.dims.z};
  for (int a = 0; a < 3; ++a) {
    g.spacing[a] = (hi[a] - lo[a]) / float(dims[a]);
    g.bricks[a] = (dims[a] + c.brick - 1u) / c.brick;
  }
  return g;
}

template <class T>
MASAV_HD inline hd::V3<T> v3(Vec3f a) {
  return hd::V3<T>{T(a.x), T(a.y), T(a.z)};
}

// Pixel (x, y) looks along normalize(forward + ndc_x * right + ndc_y * up), y = 0 the top row.
template <class T>
MASAV_HD inline hd::V3<T> pixel_direction(const RaymarchLayout& c, uint32_t x, uint32_t y) {
  const T nx = (T(x) + T(0.5)) / T(c.width) * T(2) - T(1);
  const T ny = T(1) - (T(y) + T(0.5)) / T(c.height) * T(2);
  return hd::normalize(v3<T>(c.forward) + v3<T>(c.right) * nx + v3<T>(c.up) * ny);
}

// The image is cut into kRayTile x kRayTile tiles, row-major, and each tile's pixels row-major:
// invocation id marches pixel (x, y), so that neighbouring invocations (a SIMD vector on
// lavapipe, a warp, a CPU task) march neighbouring rays through the same bricks. False for the
// padding of the last tile column and row.
constexpr uint32_t kRayTile = 8;

MASAV_HD inline uint64_t tiled_pixel_count(uint32_t width, uint32_t height) {
  return uint64_t((width + kRayTile - 1u) / kRayTile) * ((height + kRayTile - 1u) / kRayTile) *
         kRayTile * kRayTile;
}

MASAV_HD inline bool tile_pixel(const RaymarchLayout& c, uint32_t id, uint32_t& x, uint32_t& y) {
  const uint32_t tiles_x = (c.width + kRayTile - 1u) / kRayTile;
  const uint32_t tile = id / (kRayTile * kRayTile), in = id % (kRayTile * kRayTile);
  x = tile % tiles_x * kRayTile + in % kRayTile;
  y = tile / tiles_x * kRayTile + in / kRayTile;
  return x < c.width && y < c.height;
}

// The largest transfer alpha over a brick, and over the block of 2x2x2 bricks that holds it
// (engine/kernels/atom_body.h, volume_bricks): 0 means nothing there is visible.
template <class T>
struct Occupancy {
  T brick, block;
};

// The ray's t where it leaves cell ci of a grid of `count` cells of `size` voxels per axis, the ray
// being u(t) = u0 + du t in voxel coordinates (inv_du = 1 / du, 0 where du = 0). The grid's
// outermost cells reach to infinity outward, as the clamped cell index does; kFar if the ray
// never leaves.
template <class T>
MASAV_HD inline T cell_exit(hd::V3<T> u0, hd::V3<T> du, hd::V3<T> inv_du, const uint32_t ci[3],
                            const uint32_t count[3], T size) {
  T exit = T(kFar);
  for (int a = 0; a < 3; ++a) {
    const T d = hd::comp(du, a);
    T face = T(-1);
    if (d > T(0) && ci[a] + 1u < count[a]) face = T(ci[a] + 1u) * size;
    if (d < T(0) && ci[a] > 0u) face = T(ci[a]) * size;
    if (face >= T(0)) exit = hd::min_t(exit, (face - hd::comp(u0, a)) * hd::comp(inv_du, a));
  }
  return exit;
}

// The first segment at or after `i + 1` whose midpoint tn + (k + 1/2) step lies at or beyond t.
template <class T>
MASAV_HD inline uint32_t first_segment_after(T t, T tn, T step, uint32_t i, uint32_t n) {
  uint32_t next = i + 1u;
  const T first = hd::ceil_t((t - tn) / step - T(0.5));
  if (first > T(next)) next = first >= T(n) ? n : uint32_t(first);
  return next;
}

// One pixel. vol(i, j, k): voxel value; tf(k): transfer entry; occupancy(bx, by, bz): the
// Occupancy of brick (bx, by, bz).
//
// Empty space is skipped per ray segment: where the ray enters a brick, one lookup tells whether
// its 2x2x2 block of bricks, or else the brick, is empty, and the ray jumps to where it leaves
// that block or brick; an occupied brick is sampled to its exit with no further lookups. Every
// iteration advances at least one segment, so iterations <= the segment count (validated on the
// host below kMaxRaySteps). The samples taken are exactly those of the march without skipping
// whose value could be visible, so skipping does not change the image.
template <class T, class Vol, class Tf, class Occ>
MASAV_HD inline V4<T> raymarch_pixel(const RaymarchLayout& c, uint32_t px, uint32_t py, Vol&& vol,
                                     Tf&& tf, Occ&& occupancy) {
  V4<T> acc{T(0), T(0), T(0), T(0)};
  const RayGeometry g = ray_geometry(c);
  const hd::V3<T> eye = v3<T>(c.eye), dir = pixel_direction<T>(c, px, py);
  const hd::V3<T> lo = v3<T>(c.box_min), hi = v3<T>(c.box_max);
  T tn = T(0), tf_ = T(kFar);
  if (!slab(eye, dir, lo, hi, tn, tf_)) return acc;
  const T step = T(c.step), len = tf_ - tn;
  const uint32_t n = uint32_t(hd::ceil_t(len / step));
  const uint32_t dims[3] = {c.dims.x, c.dims.y, c.dims.z};
  // The ray in voxel coordinates (voxel centres at integers).
  const hd::V3<T> sp{T(g.spacing[0]), T(g.spacing[1]), T(g.spacing[2])};
  const hd::V3<T> u0{(eye.x - lo.x) / sp.x - T(0.5), (eye.y - lo.y) / sp.y - T(0.5),
                     (eye.z - lo.z) / sp.z - T(0.5)};
  const hd::V3<T> du{dir.x / sp.x, dir.y / sp.y, dir.z / sp.z};
  const hd::V3<T> inv_du{du.x != T(0) ? T(1) / du.x : T(0), du.y != T(0) ? T(1) / du.y : T(0),
                         du.z != T(0) ? T(1) / du.z : T(0)};
  const T vmin = T(c.value_min), vscale = T(c.value_scale);
  const T exponent = step / T(c.reference_step);
  const bool lerp = c.mode == Compositing::lerp;
  const bool skip = c.skip_empty && !lerp;
  const T brick = T(c.brick);
  const uint32_t blocks[3] = {(g.bricks[0] + 1u) / 2u, (g.bricks[1] + 1u) / 2u,
                              (g.bricks[2] + 1u) / 2u};
  T occupied_until = T(-1);  // the ray is in an occupied brick for t < occupied_until
  uint32_t i = 0;
  for (uint32_t it = 0; it < n && i < n; ++it) {
    const uint32_t seg = lerp ? n - 1u - i : i;
    const T s0 = tn + T(seg) * step;
    const T s1 = hd::min_t(s0 + step, tf_);
    const T tm = T(0.5) * (s0 + s1);
    const hd::V3<T> u = u0 + du * tm;
    if (skip && tm >= occupied_until) {
      uint32_t bi[3];
      for (int a = 0; a < 3; ++a) {  // clamped to >= 0 first: truncation is the floor
        const uint32_t b = uint32_t(hd::max_t(hd::comp(u, a) / brick, T(0)));
        bi[a] = hd::min_t(b, g.bricks[a] - 1u);
      }
      const Occupancy<T> o = occupancy(bi[0], bi[1], bi[2]);
      if (o.block <= T(0)) {
        const uint32_t bl[3] = {bi[0] / 2u, bi[1] / 2u, bi[2] / 2u};
        i = first_segment_after(cell_exit(u0, du, inv_du, bl, blocks, T(2) * brick), tn, step, i,
                                n);
        continue;
      }
      const T exit = cell_exit(u0, du, inv_du, bi, g.bricks, brick);
      if (o.brick <= T(0)) {
        i = first_segment_after(exit, tn, step, i, n);
        continue;
      }
      occupied_until = exit;
    }
    const T v = trilinear(u, dims, vol);
    const V4<T> col = transfer((v - vmin) * vscale, c.tf_size, tf);
    if (lerp) {
      acc.r += (col.r - acc.r) * col.a;
      acc.g += (col.g - acc.g) * col.a;
      acc.b += (col.b - acc.b) * col.a;
      acc.a += (T(1) - acc.a) * col.a;
    } else if (col.a > T(0)) {  // a transparent sample adds nothing: 1 - 1^e = 0
      const T e = seg + 1u == n ? (s1 - s0) / T(c.reference_step) : exponent;
      const T alpha = T(1) - hd::pow_t(hd::max_t(T(0), T(1) - col.a), e);
      const T wgt = (T(1) - acc.a) * alpha;
      acc.r += wgt * col.r;
      acc.g += wgt * col.g;
      acc.b += wgt * col.b;
      acc.a += wgt;
      if (acc.a >= T(c.termination_alpha)) break;
    }
    ++i;
  }
  return acc;
}

}  // namespace masav::volume
