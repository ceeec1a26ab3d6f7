#pragma once
// One pixel's march through a volume (thesis chapter 3), shared by the CPU reference (T = double)
// and CUDA (T = float); shaders/raymarch.comp is the GLSL twin: the pixel's ray and its tile, the
// ray in voxel coordinates, empty-space skipping over the bricks, and the two marches (midpoint
// samples, and pre-integrated segments). The sample's pieces are in volume_sample.h, the transfer
// function's in volume_transfer.h; including this header gives all three.
//
// Sampling: the ray's span inside the box [t_near, t_far] is cut into n = ceil(len / step)
// segments of length `step` (the last shorter); each is sampled at its midpoint. Front-to-back
// emission-absorption with the opacity of a segment of length h corrected from the transfer
// function's reference step: alpha_h = 1 - (1 - alpha)^(h / reference_step), so the image does
// not depend on the step beyond the quadrature error. For a smooth field the composited opacity
// is the midpoint rule for 1 - exp(-int kappa ds): error O(step^2) (tests: tests/test_volume.cpp).
#include <cstdint>

#include "engine/kernels/atom_params.h"
#include "engine/kernels/hd_vec.h"
#include "engine/kernels/volume_sample.h"
#include "engine/kernels/volume_transfer.h"

namespace masav::volume {

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
    g.bricks[a] = (dims[a] + ray_brick(c) - 1u) / ray_brick(c);
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
  const T nx = (T(x) + T(0.5)) / T(ray_width(c)) * T(2) - T(1);
  const T ny = T(1) - (T(y) + T(0.5)) / T(ray_height(c)) * T(2);
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
  const uint32_t tiles_x = (ray_width(c) + kRayTile - 1u) / kRayTile;
  const uint32_t tile = id / (kRayTile * kRayTile), in = id % (kRayTile * kRayTile);
  x = tile % tiles_x * kRayTile + in % kRayTile;
  y = tile / tiles_x * kRayTile + in / kRayTile;
  return x < ray_width(c) && y < ray_height(c);
}

// What one brick tells a ray (engine/kernels/atom_body.h, volume_bricks and volume_brick_skip):
// the largest transfer alpha over the brick's values (0: nothing there is visible) and its
// stride, the Chebyshev distance in bricks to the nearest brick of the other kind (>= 1): every
// brick within stride - 1 of it is empty too, or occupied too.
template <class T>
struct Occupancy {
  T brick, stride;
};

// The ray's t where it leaves the box of cells lo .. hi (per axis) of a grid of `count` cells of
// `size` voxels per axis, the ray being u(t) = u0 + du t in voxel coordinates (inv_du = 1 / du, 0
// where du = 0). The grid's outermost cells reach to infinity outward, as the clamped cell index
// does; kFar if the ray never leaves.
template <class T>
MASAV_HD inline T box_exit(hd::V3<T> u0, hd::V3<T> du, hd::V3<T> inv_du, const uint32_t lo[3],
                           const uint32_t hi[3], const uint32_t count[3], T size) {
  T exit = T(kFar);
  for (int a = 0; a < 3; ++a) {
    const T d = hd::comp(du, a);
    T face = T(-1);
    if (d > T(0) && hi[a] + 1u < count[a]) face = T(hi[a] + 1u) * size;
    if (d < T(0) && lo[a] > 0u) face = T(lo[a]) * size;
    if (face >= T(0)) exit = hd::min_t(exit, (face - hd::comp(u0, a)) * hd::comp(inv_du, a));
  }
  return exit;
}

// The first segment at or after `i + 1` whose midpoint tn + (k + 1/2) step lies at or beyond t
// (inv_step = 1 / step). A skip's latency is a chain from the sample's position to the next
// one's, so this multiplies rather than divides, and takes the ceiling by truncation (x > 1
// there) rather than the libm call that ceil is without SSE4.1.
template <class T>
MASAV_HD inline uint32_t first_segment_after(T t, T tn, T inv_step, uint32_t i, uint32_t n) {
  uint32_t next = i + 1u;
  const T x = (t - tn) * inv_step - T(0.5);  // the ceiling of x is the segment
  if (x > T(next)) {
    const uint32_t k = uint32_t(x);
    next = x >= T(n) ? n : (T(k) < x ? k + 1u : k);
  }
  return next;
}

// Which form pow_step takes for exponent e (kRayPow*). The step is usually a power-of-two
// fraction or multiple of the reference step (1/2 voxel against 1: e = 0.5 exactly), and those
// exponents take a square root or a product instead of pow, the costliest call of a sample (a
// fifth of the CPU's time).
template <class T>
MASAV_HD inline uint32_t pow_step_form(T e) {
  if (e == T(1)) return kRayPowOne;
  if (e == T(0.5)) return kRayPowHalf;
  if (e == T(0.25)) return kRayPowQuarter;
  if (e == T(2)) return kRayPowTwo;
  return kRayPowGeneral;
}

// x^e in the form `form` (pow_step_form(e)).
template <class T>
MASAV_HD inline T pow_in_form(T x, T e, uint32_t form) {
  if (form == kRayPowOne) return x;
  if (form == kRayPowHalf) return hd::sqrt_t(x);
  if (form == kRayPowQuarter) return hd::sqrt_t(hd::sqrt_t(x));
  if (form == kRayPowTwo) return x * x;
  return hd::pow_t(x, e);
}

// x^e for the opacity correction.
template <class T>
MASAV_HD inline T pow_step(T x, T e) {
  return pow_in_form(x, e, pow_step_form(e));
}

// A pixel's ray clipped to the volume's box, in voxel coordinates (voxel centres at integers),
// with the brick grid that empty-space skipping walks: what both marches start from.
template <class T>
struct VoxelRay {
  RayGeometry g;
  T tn, tf;    // where the ray enters and leaves the box
  uint32_t n;  // segments of c.step between them (the last may be shorter)
  uint32_t dims[3];
  hd::V3<T> dir;             // the ray's unit direction in the world
  hd::V3<T> u0, du, inv_du;  // voxel position u0 + du t; 1 / du (0 where du is)
  T brick;                   // voxels per brick
  uint32_t brick_shift;      // log2 of voxels per brick where that is a power of two, else 0
  T inv_step;                // 1 / c.step
};

// False when the ray misses the box.
template <class T>
MASAV_HD inline bool voxel_ray(const RaymarchLayout& c, uint32_t px, uint32_t py, VoxelRay<T>& r) {
  r.g = ray_geometry(c);
  const hd::V3<T> eye = v3<T>(c.eye), dir = pixel_direction<T>(c, px, py);
  const hd::V3<T> lo = v3<T>(c.box_min), hi = v3<T>(c.box_max);
  r.tn = T(0);
  r.tf = T(kFar);
  if (!slab(eye, dir, lo, hi, r.tn, r.tf)) return false;
  if ((c.bits & kRayClip) != 0u && !clip_span(eye, dir, ray_clip_axis(c), T(c.clip_position),
                                              (c.bits & kRayClipKeepAbove) != 0u, r.tn, r.tf))
    return false;
  r.dir = dir;
  r.n = uint32_t(hd::ceil_t((r.tf - r.tn) / T(c.step)));
  r.dims[0] = c.dims.x;
  r.dims[1] = c.dims.y;
  r.dims[2] = c.dims.z;
  const hd::V3<T> sp{T(r.g.spacing[0]), T(r.g.spacing[1]), T(r.g.spacing[2])};
  r.u0 = hd::V3<T>{(eye.x - lo.x) / sp.x - T(0.5), (eye.y - lo.y) / sp.y - T(0.5),
                   (eye.z - lo.z) / sp.z - T(0.5)};
  r.du = hd::V3<T>{dir.x / sp.x, dir.y / sp.y, dir.z / sp.z};
  r.inv_du = hd::V3<T>{r.du.x != T(0) ? T(1) / r.du.x : T(0), r.du.y != T(0) ? T(1) / r.du.y : T(0),
                       r.du.z != T(0) ? T(1) / r.du.z : T(0)};
  r.brick = T(ray_brick(c));
  r.brick_shift = 0u;
  for (uint32_t s = 1u; s < 5u; ++s)
    if ((1u << s) == ray_brick(c)) r.brick_shift = s;
  r.inv_step = T(1) / T(c.step);
  return true;
}

// What one occupancy lookup at voxel position u tells the ray: the bricks within its brick's
// stride are all empty (empty) or all occupied, up to `until`, where the ray leaves them.
template <class T>
struct SkipSpan {
  bool empty;
  T until;
};
template <class T, class Occ>
MASAV_HD inline SkipSpan<T> skip_span(const VoxelRay<T>& r, hd::V3<T> u, Occ&& occupancy) {
  // floor(u / brick) as floor(u) / brick in integers (the same brick: a rounded u / brick never
  // reaches the next integer for bricks of 2-16), and as a shift for a power of two, the usual
  // brick, since a skip's cost is a chain of dependent operations.
  const uint32_t brick = uint32_t(r.brick);
  uint32_t bi[3];
  for (int a = 0; a < 3; ++a) {  // clamped to >= 0 first: truncation is the floor
    const uint32_t v = uint32_t(hd::max_t(hd::comp(u, a), T(0)));
    const uint32_t b = r.brick_shift != 0u ? v >> r.brick_shift : v / brick;
    bi[a] = hd::min_t(b, r.g.bricks[a] - 1u);
  }
  const Occupancy<T> o = occupancy(bi[0], bi[1], bi[2]);
  // Bricks within stride - 1 of this one (a stride that is not a number from 1 to the largest
  // radius + 1 counts as 1: this brick alone).
  const uint32_t reach =
      o.stride >= T(2) && o.stride <= T(kBrickSkipMaxRadius + 1) ? uint32_t(o.stride) - 1u : 0u;
  uint32_t lo[3], hi[3];
  for (int a = 0; a < 3; ++a) {
    lo[a] = bi[a] > reach ? bi[a] - reach : 0u;
    hi[a] = hd::min_t(bi[a] + reach, r.g.bricks[a] - 1u);
  }
  return {o.brick <= T(0), box_exit(r.u0, r.du, r.inv_du, lo, hi, r.g.bricks, r.brick)};
}

// The last segment boundary at or before t (segments of `step` from tn, n of them), as a segment
// index in [0, n].
template <class T>
MASAV_HD inline uint32_t last_boundary_before(T t, T tn, T inv_step, uint32_t n) {
  const T q = (t - tn) * inv_step;
  return q >= T(n) ? n : (q > T(0) ? uint32_t(q) : 0u);
}

// One pixel with a pre-integrated transfer function (front_to_back). vol and occupancy as for
// raymarch_pixel; pt(i): entry i of the pre-integrated table (segment_mean).
//
// Segment i runs between boundaries tn + i step and the next (the last ends at the box); the
// scalar is sampled at boundaries, each shared by the two segments that meet there. Empty space
// is skipped where a whole run of segments lies inside one cube of empty bricks (skip_span): every
// value between their ends is in those bricks' ranges, whose opacity is 0, so skipping leaves the
// image as the march without skipping makes it.
template <class T, class Vol, class Pt, class Occ>
MASAV_HD inline V4<T> raymarch_pixel_preintegrated(const RaymarchLayout& c, uint32_t px,
                                                   uint32_t py, Vol&& vol, Pt&& pt,
                                                   Occ&& occupancy) {
  V4<T> acc{T(0), T(0), T(0), T(0)};
  VoxelRay<T> r;
  if (!voxel_ray(c, px, py, r)) return acc;
  const T tn = r.tn, tf_ = r.tf, step = T(c.step);
  const uint32_t n = r.n;
  const T vmin = T(c.value_min), vscale = T(c.value_scale);
  const T inv_ref = T(1) / T(c.reference_step);
  const bool skip = (c.bits & kRaySkipEmpty) != 0u;
  const bool shade = (c.bits & kRayShade) != 0u;
  const Lighting<T> light = shade ? lighting(c, r.dir) : Lighting<T>{};
  auto value_at = [&](T t) {
    return tf_pos((trilinear(r.u0 + r.du * t, r.dims, vol) - vmin) * vscale, ray_tf_size(c));
  };
  T occupied_until = T(-1);  // the ray is in an occupied brick for t < occupied_until
  TfPos<T> front{0u, T(0)};
  bool have_front = false;  // front holds the value at boundary i
  uint32_t i = 0;
  for (uint32_t it = 0; it < n && i < n; ++it) {
    const T s0 = tn + T(i) * step;
    const T s1 = hd::min_t(s0 + step, tf_);
    if (skip && s0 >= occupied_until) {
      const SkipSpan<T> span = skip_span(r, r.u0 + r.du * s0, occupancy);
      if (!span.empty) occupied_until = span.until;
      const uint32_t j = span.empty && span.until >= T(0)
                             ? last_boundary_before(span.until, tn, r.inv_step, n)
                             : 0u;
      if (j > i) {  // segments i .. j-1 end inside the empty cell
        i = j;
        have_front = false;
        continue;
      }
    }
    if (!have_front) front = value_at(s0);
    const TfPos<T> back = value_at(s1);
    const V4<T> m = segment_mean(front, back, pt);
    front = back;
    have_front = true;
    if (m.a > T(0)) {  // alpha = 1 - exp(-depth); colour = emission / depth per unit alpha
      const T alpha = T(1) - hd::exp_t(-m.a * (s1 - s0) * inv_ref);
      const T wgt = (T(1) - acc.a) * alpha;
      if (shade) {  // the segment's mean colour, lit at its midpoint
        const T inv = T(1) / m.a;
        const V4<T> col =
            shade_at(V4<T>{m.r * inv, m.g * inv, m.b * inv, m.a},
                     r.u0 + r.du * (T(0.5) * (s0 + s1)), r.dims, r.g.spacing, vscale, light, vol);
        acc.r += wgt * col.r;
        acc.g += wgt * col.g;
        acc.b += wgt * col.b;
      } else {
        const T cw = wgt / m.a;
        acc.r += cw * m.r;
        acc.g += cw * m.g;
        acc.b += cw * m.b;
      }
      acc.a += wgt;
      if (acc.a >= T(c.termination_alpha)) break;
    }
    ++i;
  }
  return acc;
}

// One pixel. vol(i, j, k): voxel value; tf(k): transfer entry; occupancy(bx, by, bz): the
// Occupancy of brick (bx, by, bz).
//
// Empty space is skipped per ray segment: where the ray enters a brick, one lookup tells whether
// it is empty, and how far around it every brick is of its kind (its stride); the ray jumps to
// where it leaves that cube of empty bricks, or samples a cube of occupied ones to its exit with
// no further lookups. Every
// iteration advances at least one segment, so iterations <= the segment count (validated on the
// host below kMaxRaySteps). The samples taken are exactly those of the march without skipping
// whose value could be visible, so skipping does not change the image.
template <class T, class Vol, class Tf, class Occ>
MASAV_HD inline V4<T> raymarch_pixel(const RaymarchLayout& c, uint32_t px, uint32_t py, Vol&& vol,
                                     Tf&& tf, Occ&& occupancy) {
  V4<T> acc{T(0), T(0), T(0), T(0)};
  VoxelRay<T> r;
  if (!voxel_ray(c, px, py, r)) return acc;
  const T tn = r.tn, tf_ = r.tf, step = T(c.step);
  const uint32_t n = r.n;
  const T vmin = T(c.value_min), vscale = T(c.value_scale);
  const T exponent = step / T(c.reference_step);
  const bool lerp = (c.bits & kRayLerp) != 0u;
  const bool skip = (c.bits & kRaySkipEmpty) != 0u && !lerp;
  const bool shade = (c.bits & kRayShade) != 0u;
  const Lighting<T> light = shade ? lighting(c, r.dir) : Lighting<T>{};
  T occupied_until = T(-1);  // the ray is in an occupied brick for t < occupied_until
  uint32_t i = 0;
  for (uint32_t it = 0; it < n && i < n; ++it) {
    const uint32_t seg = lerp ? n - 1u - i : i;
    const T s0 = tn + T(seg) * step;
    const T s1 = hd::min_t(s0 + step, tf_);
    const T tm = T(0.5) * (s0 + s1);
    const hd::V3<T> u = r.u0 + r.du * tm;
    if (skip && tm >= occupied_until) {
      const SkipSpan<T> span = skip_span(r, u, occupancy);
      if (span.empty) {
        i = first_segment_after(span.until, tn, r.inv_step, i, n);
        continue;
      }
      occupied_until = span.until;
    }
    const T v = trilinear(u, r.dims, vol);
    V4<T> col = transfer((v - vmin) * vscale, ray_tf_size(c), tf);
    if (shade && col.a > T(0)) col = shade_at(col, u, r.dims, r.g.spacing, vscale, light, vol);
    if (lerp) {
      acc.r += (col.r - acc.r) * col.a;
      acc.g += (col.g - acc.g) * col.a;
      acc.b += (col.b - acc.b) * col.a;
      acc.a += (T(1) - acc.a) * col.a;
    } else if (col.a > T(0)) {  // a transparent sample adds nothing: 1 - 1^e = 0
      const T e = seg + 1u == n ? (s1 - s0) / T(c.reference_step) : exponent;
      const T alpha = T(1) - pow_step(hd::max_t(T(0), T(1) - col.a), e);
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
