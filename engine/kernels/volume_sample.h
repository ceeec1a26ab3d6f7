#pragma once
// One sample of a volume ray cast (thesis chapter 3), shared by the CPU reference (T = double) and
// CUDA (T = float): the raymarch layout's packed fields, the slab ray-box test (thesis Alg. 3.1),
// the clipping plane, trilinear sampling, and gradient (Blinn-Phong) shading of the colour the
// transfer function (volume_transfer.h) gave. shaders/common/slab.glsl and
// shaders/common/volume.glsl are the GLSL twins; volume_math.h marches a pixel's ray from these.
#include <cstdint>

#include "engine/kernels/atom_params.h"
#include "engine/kernels/hd_vec.h"
#include "engine/kernels/volume_transfer.h"

namespace masav::volume {

constexpr float kFar = 1e30f;

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

}  // namespace masav::volume
