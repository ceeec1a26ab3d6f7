#pragma once
// Volume ray casting (thesis chapter 3), shared by the CPU reference (T = double) and CUDA
// (T = float); shaders/common/volume.glsl is the GLSL twin: the slab ray-box test (thesis
// Alg. 3.1), the clipping plane, trilinear sampling, gradient (Blinn-Phong) shading, the 1-D
// transfer function, and one pixel's march.
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

// The small integers RaymarchLayout packs into shared words.
MASAV_HD inline uint32_t ray_width(const RaymarchLayout& c) {
  return c.image_size & 0xffffu;
}
MASAV_HD inline uint32_t ray_height(const RaymarchLayout& c) {
  return c.image_size >> 16;
}
MASAV_HD inline uint32_t ray_brick(const RaymarchLayout& c) {
  return (c.bits >> kRayBrickShift) & 31u;
}
MASAV_HD inline uint32_t ray_tf_size(const RaymarchLayout& c) {
  return (c.bits >> kRayTfSizeShift) & 8191u;
}
MASAV_HD inline uint32_t ray_clip_axis(const RaymarchLayout& c) {
  return (c.bits >> kRayClipAxisShift) & 3u;
}

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

// The clipping plane: the ray o + d t keeps the part of [t_near, t_far] whose coordinate on
// `axis` lies at or above `plane` (keep_above) or at or below it; false when nothing is left.
// Clipping the span rather than testing each sample costs nothing per sample, and the kept span
// is sampled from its own start as an unclipped ray would be.
template <class T>
MASAV_HD inline bool clip_span(hd::V3<T> o, hd::V3<T> d, uint32_t axis, T plane, bool keep_above,
                               T& t_near, T& t_far) {
  const T oa = hd::comp(o, int(axis)), da = hd::comp(d, int(axis));
  if (da == T(0)) return keep_above ? oa >= plane : oa <= plane;
  const T t = (plane - oa) / da;
  if ((da > T(0)) == keep_above) {
    if (t > t_near) t_near = t;
  } else if (t < t_far) {
    t_far = t;
  }
  return t_near < t_far;
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

// unorm16 and snorm16 as GLSL's unpackUnorm2x16 / unpackSnorm2x16 read one half of a word.
template <class T>
MASAV_HD inline T unorm16(uint32_t bits) {
  return T(bits & 0xffffu) / T(65535);
}
template <class T>
MASAV_HD inline T snorm16(uint32_t bits) {
  const uint32_t u = bits & 0xffffu;
  const T s = u >= 32768u ? -T(65536u - u) : T(u);
  return hd::max_t(s / T(32767), T(-1));
}

// The unit direction an octahedral pair of snorm16 encodes (raymarch_layout writes it).
template <class T>
MASAV_HD inline hd::V3<T> octahedral(uint32_t bits) {
  T x = snorm16<T>(bits), y = snorm16<T>(bits >> 16);
  const T z = T(1) - hd::abs_t(x) - hd::abs_t(y);
  if (z < T(0)) {
    const T fx = (T(1) - hd::abs_t(y)) * (x < T(0) ? T(-1) : T(1));
    y = (T(1) - hd::abs_t(x)) * (y < T(0) ? T(-1) : T(1));
    x = fx;
  }
  return hd::normalize(hd::V3<T>{x, y, z});
}

// Blinn-Phong per ray: the unit vector towards the light and the half vector between it and the
// viewer (the headlight: both -dir), and the material.
template <class T>
struct Lighting {
  hd::V3<T> l, h;
  T ambient, diffuse, specular, shininess;
};

template <class T>
MASAV_HD inline Lighting<T> lighting(const RaymarchLayout& c, hd::V3<T> dir) {
  Lighting<T> L;
  const hd::V3<T> v = dir * T(-1);
  L.l = v;
  L.h = v;
  if ((c.bits & kRayHeadlight) == 0u) {
    L.l = octahedral<T>(c.shade_light);
    const hd::V3<T> s = L.l + v;
    const T len = hd::length(s);
    L.h = len > T(1e-6) ? s * (T(1) / len) : L.l;  // light straight behind the volume: h = l
  }
  L.ambient = unorm16<T>(c.shade_ambient_diffuse);
  L.diffuse = unorm16<T>(c.shade_ambient_diffuse >> 16);
  L.specular = unorm16<T>(c.shade_specular);
  L.shininess = unorm16<T>(c.shade_specular >> 16) * T(kRayMaxShininess);
  return L;
}

// Central differences of the trilinear field one voxel either side of u, per axis:
// trilinear(u + e_a) - trilinear(u - e_a). Where u is a voxel or more inside the outermost
// centres on every axis with its cell's far neighbour in range too, the six lookups share u's
// cell and weights, shifted by one voxel, and the 32 voxels they read are read once; elsewhere
// (clamping changes the cells) they are six trilinear lookups.
template <class T, class Vol>
MASAV_HD inline hd::V3<T> central_gradient(hd::V3<T> u, const uint32_t dims[3], Vol&& vol) {
  bool inner = true;
  for (int a = 0; a < 3; ++a)
    inner = inner && hd::comp(u, a) >= T(1) && hd::comp(u, a) < T(dims[a] - 2u);
  if (!inner) {
    const hd::V3<T> ex{T(1), T(0), T(0)}, ey{T(0), T(1), T(0)}, ez{T(0), T(0), T(1)};
    return hd::V3<T>{trilinear(u + ex, dims, vol) - trilinear(u - ex, dims, vol),
                     trilinear(u + ey, dims, vol) - trilinear(u - ey, dims, vol),
                     trilinear(u + ez, dims, vol) - trilinear(u - ez, dims, vol)};
  }
  const uint32_t i = uint32_t(u.x), j = uint32_t(u.y), k = uint32_t(u.z);  // u >= 1: the floor
  const T fx = u.x - T(i), fy = u.y - T(j), fz = u.z - T(k);
  const T wx[2] = {T(1) - fx, fx}, wy[2] = {T(1) - fy, fy}, wz[2] = {T(1) - fz, fz};
  T c[2][2][2];  // the cell's corners: c[z][y][x] = vol(i + x, j + y, k + z)
  for (uint32_t z = 0; z < 2u; ++z)
    for (uint32_t y = 0; y < 2u; ++y)
      for (uint32_t x = 0; x < 2u; ++x) c[z][y][x] = vol(i + x, j + y, k + z);
  T gx = T(0), gy = T(0), gz = T(0);
  for (uint32_t b = 0; b < 2u; ++b)
    for (uint32_t a = 0; a < 2u; ++a) {
      // gx: the x difference on the cell's edge at (j + a, k + b), weighted wy[a] wz[b]; gy, gz
      // likewise on the edges along y and z.
      const T dx = wx[0] * (c[b][a][1] - vol(i - 1u, j + a, k + b)) +
                   wx[1] * (vol(i + 2u, j + a, k + b) - c[b][a][0]);
      const T dy = wy[0] * (c[b][1][a] - vol(i + a, j - 1u, k + b)) +
                   wy[1] * (vol(i + a, j + 2u, k + b) - c[b][0][a]);
      const T dz = wz[0] * (c[1][b][a] - vol(i + a, j + b, k - 1u)) +
                   wz[1] * (vol(i + a, j + b, k + 2u) - c[0][b][a]);
      gx += wy[a] * wz[b] * dx;
      gy += wx[a] * wz[b] * dy;
      gz += wx[a] * wy[b] * dz;
    }
  return hd::V3<T>{gx, gy, gz};
}

// A sample's shaded colour: rgb * (ambient + diffuse |n.l|) + specular (n.h)^shininess, with n the
// normalised gradient of the trilinear field by central differences one voxel either side
// (spacing: world units per voxel on each axis). Two-sided: n is turned towards the light. Where
// the field changes by less than 1e-4 of its value range per voxel there is no surface to light
// and the colour stays as the transfer function gave it.
template <class T, class Vol>
MASAV_HD inline V4<T> shade_at(V4<T> col, hd::V3<T> u, const uint32_t dims[3],
                               const float spacing[3], T value_scale, const Lighting<T>& L,
                               Vol&& vol) {
  const hd::V3<T> g = central_gradient(u, dims, vol);
  const T gx = g.x, gy = g.y, gz = g.z;
  const T largest = hd::max_t(hd::abs_t(gx), hd::max_t(hd::abs_t(gy), hd::abs_t(gz)));
  if (largest * hd::abs_t(value_scale) < T(2e-4)) return col;  // 2 voxels apart: 1e-4 per voxel
  hd::V3<T> n =
      hd::normalize(hd::V3<T>{gx / T(spacing[0]), gy / T(spacing[1]), gz / T(spacing[2])});
  T ndl = hd::dot(n, L.l);
  if (ndl < T(0)) {
    n = n * T(-1);
    ndl = -ndl;
  }
  const T ndh = hd::max_t(hd::dot(n, L.h), T(0));
  const T lit = L.ambient + L.diffuse * ndl;
  const T spec = ndh > T(0) ? L.specular * hd::pow_t(ndh, L.shininess) : T(0);
  return V4<T>{col.r * lit + spec, col.g * lit + spec, col.b * lit + spec, col.a};
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

// Pre-integration (Engel, Kraus and Ertl 2001, from 1-D integral tables): along a segment the
// scalar is taken to change linearly from its value at the segment's front to that at its back,
// and the segment's opacity and colour are integrated over that change instead of read at one
// point, so a step of a voxel or more keeps the accuracy of a finer one.
//
// Entry k of the transfer function sits at x = k (x = normalised value * (size - 1)); piece k runs
// from entry k to k + 1. Per entry the table holds the optical depth tau = -ln(1 - alpha) per
// reference step and the emission colour * tau, both taken as linear across each piece (the
// midpoint rule interpolates alpha instead: the two agree to second order in the entry spacing).
// The table (engine/atom/preintegration.cpp builds it in double) holds kPreintegratedPerEntry
// Real4 per entry k:
//   [3k]     (emission r, g, b, depth) at entry k
//   [3k + 1] their integral over x from entry 0 to entry k, rounded to float
//   [3k + 2] what the rounding left (integral - the float), so that an fp32 backend differences
//            two integrals to about double precision
template <class T>
struct TfPos {
  uint32_t k;  // the piece, <= size - 2
  T w;         // where in it, [0, 1]
};

template <class T>
MASAV_HD inline TfPos<T> tf_pos(T v, uint32_t size) {
  const T x = hd::clamp_t(v, T(0), T(1)) * T(size - 1u);
  uint32_t k = uint32_t(x);
  if (k > size - 2u) k = size - 2u;
  return TfPos<T>{k, x - T(k)};
}

template <class T>
MASAV_HD inline V4<T> lerp4(V4<T> a, V4<T> b, T w) {
  return V4<T>{a.r + (b.r - a.r) * w, a.g + (b.g - a.g) * w, a.b + (b.b - a.b) * w,
               a.a + (b.a - a.a) * w};
}

// The mean (emission, depth) over the values between a and b, in either order. pt(i): table entry
// i. Within one piece, or less than 1/16 of an entry apart: the value midway (exact for a linear
// piece, and free of the cancellation that differencing two close integrals has); in
// neighbouring pieces: the two parts, each its length times its midway value; farther apart: the
// difference of the integrals over the length.
template <class T, class Pt>
MASAV_HD inline V4<T> segment_mean(TfPos<T> a, TfPos<T> b, Pt&& pt) {
  TfPos<T> f = a, e = b;
  if (b.k < a.k || (b.k == a.k && b.w < a.w)) {
    f = b;
    e = a;
  }
  const T len = T(e.k - f.k) + (e.w - f.w);
  if (e.k == f.k || len < T(0.0625)) {
    uint32_t k = f.k;
    T w = f.w + T(0.5) * len;
    if (w > T(1)) {  // the midpoint is in e's piece (only then can w pass 1)
      k = e.k;
      w -= T(1);
    }
    return lerp4(pt(3u * k), pt(3u * k + 3u), w);
  }
  const V4<T> p0 = pt(3u * f.k), p1 = pt(3u * f.k + 3u);
  const T inv = T(1) / len;
  if (e.k == f.k + 1u) {
    const V4<T> p2 = pt(3u * e.k + 3u);
    const T lf = T(1) - f.w;
    const V4<T> mf = lerp4(p0, p1, T(0.5) * (T(1) + f.w)), me = lerp4(p1, p2, T(0.5) * e.w);
    return V4<T>{(mf.r * lf + me.r * e.w) * inv, (mf.g * lf + me.g * e.w) * inv,
                 (mf.b * lf + me.b * e.w) * inv, (mf.a * lf + me.a * e.w) * inv};
  }
  // The integral from entry k to k + w: w times the value at k + w/2.
  const V4<T> pf = lerp4(p0, p1, T(0.5) * f.w);
  const V4<T> pe = lerp4(pt(3u * e.k), pt(3u * e.k + 3u), T(0.5) * e.w);
  const V4<T> hf = pt(3u * f.k + 1u), lf = pt(3u * f.k + 2u);
  const V4<T> he = pt(3u * e.k + 1u), le = pt(3u * e.k + 2u);
  return V4<T>{((he.r - hf.r) + (le.r - lf.r) + pe.r * e.w - pf.r * f.w) * inv,
               ((he.g - hf.g) + (le.g - lf.g) + pe.g * e.w - pf.g * f.w) * inv,
               ((he.b - hf.b) + (le.b - lf.b) + pe.b * e.w - pf.b * f.w) * inv,
               ((he.a - hf.a) + (le.a - lf.a) + pe.a * e.w - pf.a * f.w) * inv};
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

// The last segment boundary at or before t (segments of `step` from tn, n of them), as a segment
// index in [0, n].
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
