#pragma once
// The 1-D transfer function as the raymarch reads it, shared by the CPU reference (T = double)
// and CUDA (T = float): a sample's colour and opacity from its normalised value (transfer), and
// the pre-integrated table's lookups (tf_pos, segment_mean), which give a whole segment's mean
// instead. shaders/common/volume.glsl (transfer) and shaders/common/preintegration.glsl are the
// GLSL twins; engine/volume/preintegration.cpp builds the table on the host.
#include <cstdint>

#include "engine/kernels/hd_vec.h"

namespace masav::volume {

// RGBA: what the transfer function gives a sample, and what a ray composites.
template <class T>
struct V4 {
  T r, g, b, a;
};

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
// The table (engine/volume/preintegration.cpp builds it in double) holds kPreintegratedPerEntry
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

}  // namespace masav::volume
