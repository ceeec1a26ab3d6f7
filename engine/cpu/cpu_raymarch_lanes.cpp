// Several rays at a time (see cpu_raymarch_lanes.h): each lane of a SIMD vector holds one ray's
// state, every operation of a sample runs across the lanes, and nothing per sample branches on
// the data: a transparent sample composites a weight of exactly 0.
#include "engine/cpu/cpu_raymarch_lanes.h"

#include <vector>

#if defined(__SSE__)
#include <immintrin.h>
#endif

namespace masav::cpu {

namespace {

// Rays marched together: one SSE vector. (Eight, as two SSE vectors without AVX, ran slower than
// the scalar march: GCC moves such vectors through memory.)
constexpr int kRayLanes = 4;
using Vf = float __attribute__((vector_size(4 * kRayLanes)));
using Vi = int32_t __attribute__((vector_size(4 * kRayLanes)));

Vf splat(float x) {
  return Vf{} + x;
}

// hd::min_t and hd::max_t across lanes: a < b ? a : b, a > b ? a : b (the same NaN behaviour).
Vf vmin(Vf a, Vf b) {
  return a < b ? a : b;
}
Vf vmax(Vf a, Vf b) {
  return a > b ? a : b;
}
Vf vclamp(Vf v, Vf lo, Vf hi) {
  return v < lo ? lo : (v > hi ? hi : v);
}

// Correctly rounded square root per lane, as sqrtf gives it.
Vf vsqrt(Vf x) {
#if defined(__SSE__)
  Vf r;
  for (int k = 0; k < kRayLanes; k += 4) {
    const __m128 q = _mm_sqrt_ps(_mm_loadu_ps(reinterpret_cast<const float*>(&x) + k));
    _mm_storeu_ps(reinterpret_cast<float*>(&r) + k, q);
  }
  return r;
#else
  Vf r;
  for (int k = 0; k < kRayLanes; ++k) r[k] = hd::sqrt_t(x[k]);
  return r;
#endif
}

// Whether any lane of a comparison's result is set.
bool any_lane(Vi m) {
#if defined(__SSE__)
  if constexpr (kRayLanes == 4) return _mm_movemask_ps(_mm_castsi128_ps(__m128i(m))) != 0;
#endif
  bool any = false;
  for (int k = 0; k < kRayLanes; ++k) any = any || m[k] != 0;
  return any;
}

class LaneMarch {
 public:
  LaneMarch(const RaymarchLayout& c, const float* volume, const hd::V4<float>* tf,
            const hd::V4<float>* bricks, double* image)
      : c_(c), volume_(volume), tf_(tf), bricks_(bricks), image_(image) {
    step_ = c.step;
    inv_step_ = 1.0f / step_;
    exponent_ = step_ / c.reference_step;
    skip_ = (c.bits & kRaySkipEmpty) != 0u;
    shade_ = (c.bits & kRayShade) != 0u;
    const volume::RayGeometry g = volume::ray_geometry(c);
    for (int a = 0; a < 3; ++a) nb_[a] = g.bricks[a];
    brick_ = volume::ray_brick(c);
    brick_shift_ = 0;
    for (int sh = 1; sh < 5; ++sh)
      if ((1u << sh) == brick_) brick_shift_ = sh;
    dims_[0] = c.dims.x;
    dims_[1] = c.dims.y;
    dims_[2] = c.dims.z;
    tf_size_ = volume::ray_tf_size(c);
  }

  void run(uint64_t begin, uint64_t end) {
    next_ = begin;
    end_ = end;
    bool any = false;
    for (int k = 0; k < kRayLanes; ++k) any = start(k) || any;
    while (any) {
      const Vf segf = __builtin_convertvector(seg_, Vf);
      const Vf s0 = tn_ + segf * step_;
      const Vf s1 = vmin(s0 + step_, tf_end_);
      const Vf tm = 0.5f * (s0 + s1);
      const Vf u[3] = {u0_[0] + du_[0] * tm, u0_[1] + du_[1] * tm, u0_[2] + du_[2] * tm};
      Vf col[4];
      classify(u, col);
      if (shade_) shade(u, col);
      // The opacity of a segment of length s1 - s0: 1 - (1 - alpha)^e (volume::pow_step).
      const Vi last = seg_ + 1 == n_;
      Vf alpha;
      const Vf om = vmax(splat(0.0f), 1.0f - col[3]);
      if (exponent_ == 0.5f && !any_lane(last)) {  // the usual step, half the reference
        alpha = 1.0f - vsqrt(om);
      } else {
        const Vf e = last ? (s1 - s0) / c_.reference_step : splat(exponent_);
        for (int k = 0; k < kRayLanes; ++k) alpha[k] = 1.0f - volume::pow_step(om[k], e[k]);
      }
      // raymarch_pixel composites only samples with alpha > 0 (NaN included in "not"); here the
      // others add exactly 0.
      const Vi visible = col[3] > 0.0f;
      const Vf wgt = visible ? (1.0f - acc_[3]) * alpha : splat(0.0f);
      for (int ch = 0; ch < 3; ++ch) acc_[ch] += visible ? wgt * col[ch] : splat(0.0f);
      acc_[3] += wgt;
      seg_ = skip_ ? after(u, seg_) : seg_ + 1;
      const Vi done = (seg_ >= n_) | (acc_[3] >= c_.termination_alpha);
      if (!any_lane(done)) continue;
      any = false;
      for (int k = 0; k < kRayLanes; ++k) {
        if (done[k] && active_[k]) {
          write(k);
          start(k);
        }
        any = any || active_[k];
      }
    }
  }

 private:
  // Lane k takes the next pixel with a ray into the box (pixels whose ray misses it are written
  // black); with none left it idles, marching one harmless sample per step whose results nobody
  // reads. False then.
  bool start(int k) {
    active_[k] = false;
    acc_[0][k] = acc_[1][k] = acc_[2][k] = acc_[3][k] = 0.0f;
    while (next_ < end_) {
      const uint32_t id = uint32_t(next_++);
      uint32_t x, y;
      if (!volume::tile_pixel(c_, id, x, y)) continue;
      x_[k] = x;
      y_[k] = y;
      volume::VoxelRay<float> r;
      if (!volume::voxel_ray(c_, x, y, r)) {
        write(k);
        continue;
      }
      if (r.n == 0u) {  // a ray along the box's surface
        write(k);
        continue;
      }
      seg_[k] = 0;
      n_[k] = int32_t(r.n);
      tn_[k] = r.tn;
      tf_end_[k] = r.tf;
      for (int a = 0; a < 3; ++a) {
        u0_[a][k] = hd::comp(r.u0, a);
        du_[a][k] = hd::comp(r.du, a);
        inv_du_[a][k] = hd::comp(r.inv_du, a);
      }
      if (shade_) {
        light_[k] = volume::lighting(c_, r.dir);
        spacing_[0] = r.g.spacing[0];
        spacing_[1] = r.g.spacing[1];
        spacing_[2] = r.g.spacing[2];
      }
      active_[k] = true;
      return true;
    }
    seg_[k] = 0;
    n_[k] = 1;  // at the first voxel's centre
    tn_[k] = tf_end_[k] = 0.0f;
    for (int a = 0; a < 3; ++a) u0_[a][k] = du_[a][k] = inv_du_[a][k] = 0.0f;
    acc_[3][k] = 2.0f;  // never terminates a live lane: `done` is ignored for idle ones
    return false;
  }

  void write(int k) const {
    double* px = image_ + 4 * (size_t(y_[k]) * volume::ray_width(c_) + x_[k]);
    for (int ch = 0; ch < 4; ++ch) px[ch] = acc_[ch][k];
  }

  // The segment each lane samples after segment seg, whose midpoint is at u: where that point's
  // brick is empty, the first segment past the cube of empty bricks its stride spans
  // (volume::skip_span, box_exit and first_segment_after across lanes), else seg + 1. Unlike
  // raymarch_pixel, a lane looks its brick up at every sample, also inside a cube of occupied
  // bricks: that costs less here than a branch on where each lane's cube ends.
  Vi after(const Vf u[3], Vi seg) const {
    const Vi next = seg + 1;
    Vi b[3];
    for (int a = 0; a < 3; ++a) {  // clamped to >= 0 first: truncation is the floor
      const Vi v = __builtin_convertvector(vmax(u[a], splat(0.0f)), Vi);
      b[a] = brick_shift_ != 0 ? v >> brick_shift_ : v / int32_t(brick_);
      b[a] = b[a] < int32_t(nb_[a] - 1u) ? b[a] : Vi{} + int32_t(nb_[a] - 1u);
    }
    Vf occupied, stride;
    for (int k = 0; k < kRayLanes; ++k) {
      const hd::V4<float> o =
          bricks_[(size_t(b[2][k]) * nb_[1] + uint32_t(b[1][k])) * nb_[0] + uint32_t(b[0][k])];
      occupied[k] = o.z;
      stride[k] = o.w;
    }
    const Vi empty = occupied <= 0.0f;
    if (!any_lane(empty)) return next;
    const Vi valid = (stride >= 2.0f) & (stride <= float(kBrickSkipMaxRadius + 1));
    const Vi reach = valid ? __builtin_convertvector(stride, Vi) - 1 : Vi{};
    Vf exit = splat(volume::kFar);
    for (int a = 0; a < 3; ++a) {
      const Vi lo = b[a] > reach ? b[a] - reach : Vi{};
      Vi hi = b[a] + reach;
      hi = hi < int32_t(nb_[a] - 1u) ? hi : Vi{} + int32_t(nb_[a] - 1u);
      const Vf d = du_[a];
      Vf face = splat(-1.0f);
      face = (d > 0.0f) & (hi + 1 < int32_t(nb_[a]))
                 ? __builtin_convertvector(hi + 1, Vf) * float(brick_)
                 : face;
      face = (d < 0.0f) & (lo > 0) ? __builtin_convertvector(lo, Vf) * float(brick_) : face;
      exit = face >= 0.0f ? vmin(exit, (face - u0_[a]) * inv_du_[a]) : exit;
    }
    const Vf x = (exit - tn_) * inv_step_ - 0.5f;  // the ceiling of x is the segment
    const Vf nf = __builtin_convertvector(n_, Vf);
    const Vi k = __builtin_convertvector(vmin(x, nf), Vi);
    const Vi ceil = __builtin_convertvector(k, Vf) < x ? k + 1 : k;
    const Vi past = x >= nf ? n_ : ceil;
    const Vi jump = x > __builtin_convertvector(next, Vf) ? past : next;
    return empty ? jump : next;
  }

  // Trilinear value and transfer colour of every lane's sample, as volume::trilinear and
  // volume::transfer compute them (the same operations in the same order, across lanes).
  void classify(const Vf u[3], Vf col[4]) const {
    Vi i0[3];
    Vf f[3];
    for (int a = 0; a < 3; ++a) {
      const Vf c = vclamp(u[a], splat(0.0f), splat(float(dims_[a] - 1u)));
      i0[a] = __builtin_convertvector(c, Vi);  // c >= 0: truncation is the floor
      f[a] = c - __builtin_convertvector(i0[a], Vf);
    }
    // The padded layout holds the clamped neighbour (i + 1 on the last voxel reads the last one
    // again, as volume::trilinear's i1 does), so the corners are base + fixed offsets and each
    // x-neighbour pair is adjacent.
    const size_t px = dims_[0] + 1u, pxy = px * (dims_[1] + 1u);
    size_t base[kRayLanes];
    for (int k = 0; k < kRayLanes; ++k)
      base[k] = (uint32_t(i0[2][k]) * size_t(dims_[1] + 1u) + uint32_t(i0[1][k])) * px +
                uint32_t(i0[0][k]);
    Vf v000, v100, v010, v110, v001, v101, v011, v111;
#if defined(__SSE__)
    if constexpr (kRayLanes == 4) {
      __m128 lo[4], hi[4];  // per lane: (x0, x1) at y0 then y1, at z0 (lo) and z1 (hi)
      for (int k = 0; k < 4; ++k) {
        const float* q = volume_ + base[k];
        auto pair = [](const float* at) {
          return _mm_castpd_ps(_mm_load_sd(reinterpret_cast<const double*>(at)));
        };
        lo[k] = _mm_movelh_ps(pair(q), pair(q + px));
        hi[k] = _mm_movelh_ps(pair(q + pxy), pair(q + pxy + px));
      }
      _MM_TRANSPOSE4_PS(lo[0], lo[1], lo[2], lo[3]);
      _MM_TRANSPOSE4_PS(hi[0], hi[1], hi[2], hi[3]);
      v000 = Vf(lo[0]), v100 = Vf(lo[1]), v010 = Vf(lo[2]), v110 = Vf(lo[3]);
      v001 = Vf(hi[0]), v101 = Vf(hi[1]), v011 = Vf(hi[2]), v111 = Vf(hi[3]);
    } else
#endif
    {
      for (int k = 0; k < kRayLanes; ++k) {
        const float* q = volume_ + base[k];
        v000[k] = q[0], v100[k] = q[1], v010[k] = q[px], v110[k] = q[px + 1];
        v001[k] = q[pxy], v101[k] = q[pxy + 1], v011[k] = q[pxy + px], v111[k] = q[pxy + px + 1];
      }
    }
    const Vf gx = 1.0f - f[0], gy = 1.0f - f[1], gz = 1.0f - f[2];
    const Vf c00 = v000 * gx + v100 * f[0];
    const Vf c10 = v010 * gx + v110 * f[0];
    const Vf c01 = v001 * gx + v101 * f[0];
    const Vf c11 = v011 * gx + v111 * f[0];
    const Vf c0 = c00 * gy + c10 * f[1];
    const Vf c1 = c01 * gy + c11 * f[1];
    const Vf v = c0 * gz + c1 * f[2];
    const Vf x = vclamp((v - c_.value_min) * c_.value_scale, splat(0.0f), splat(1.0f)) *
                 float(tf_size_ - 1u);
    Vi e = __builtin_convertvector(x, Vi);
    e = e > int32_t(tf_size_ - 2u) ? Vi{} + int32_t(tf_size_ - 2u) : e;
    e = e < 0 ? Vi{} : e;  // a NaN value: entry 0, as the scalar march's conversion gives
    const Vf w = x - __builtin_convertvector(e, Vf);
    Vf a[4], b[4];
    entries(e, a, b);
    for (int ch = 0; ch < 4; ++ch) col[ch] = a[ch] + (b[ch] - a[ch]) * w;
  }

  // Transfer entries e and e + 1 of each lane, channel by channel: four lanes' RGBA loaded whole
  // and transposed where SSE is there.
  void entries(Vi e, Vf a[4], Vf b[4]) const {
#if defined(__SSE__)
    if constexpr (kRayLanes == 4) {
      __m128 p[4], q[4];
      for (int k = 0; k < 4; ++k) {
        const float* t = &tf_[uint32_t(e[k])].x;
        p[k] = _mm_load_ps(t);  // hd::V4 is 16-byte aligned
        q[k] = _mm_load_ps(t + 4);
      }
      _MM_TRANSPOSE4_PS(p[0], p[1], p[2], p[3]);
      _MM_TRANSPOSE4_PS(q[0], q[1], q[2], q[3]);
      for (int ch = 0; ch < 4; ++ch) {
        a[ch] = Vf(p[ch]);
        b[ch] = Vf(q[ch]);
      }
      return;
    }
#endif
    for (int k = 0; k < kRayLanes; ++k) {
      const hd::V4<float> p = tf_[uint32_t(e[k])], q = tf_[uint32_t(e[k]) + 1u];
      a[0][k] = p.x, a[1][k] = p.y, a[2][k] = p.z, a[3][k] = p.w;
      b[0][k] = q.x, b[1][k] = q.y, b[2][k] = q.z, b[3][k] = q.w;
    }
  }

  // volume::shade_at per lane whose sample is visible (the scalar march shades those alone).
  void shade(const Vf u[3], Vf col[4]) const {
    auto vat = [this](uint32_t i, uint32_t j, uint32_t k) {
      return volume_[(size_t(k) * (dims_[1] + 1u) + j) * (dims_[0] + 1u) + i];
    };
    for (int k = 0; k < kRayLanes; ++k) {
      if (!active_[k] || !(col[3][k] > 0.0f)) continue;
      const volume::V4<float> lit =
          volume::shade_at(volume::V4<float>{col[0][k], col[1][k], col[2][k], col[3][k]},
                           hd::V3<float>{u[0][k], u[1][k], u[2][k]}, dims_, spacing_,
                           c_.value_scale, light_[k], vat);
      col[0][k] = lit.r;
      col[1][k] = lit.g;
      col[2][k] = lit.b;
    }
  }

  const RaymarchLayout& c_;
  const float* volume_;
  const hd::V4<float>* tf_;
  const hd::V4<float>* bricks_;
  double* image_;
  float step_, inv_step_, exponent_;
  bool skip_, shade_;
  uint32_t nb_[3], brick_, tf_size_, dims_[3];
  int brick_shift_;  // log2 of brick where it is a power of two, else 0
  float spacing_[3] = {1, 1, 1};
  uint64_t next_ = 0, end_ = 0;
  // Per lane: the next segment and the segment count, the ray's span and voxel-space line, the
  // composited colour, the pixel.
  Vi seg_{}, n_{};
  Vf tn_{}, tf_end_{}, u0_[3]{}, du_[3]{}, inv_du_[3]{}, acc_[4]{};
  uint32_t x_[kRayLanes] = {}, y_[kRayLanes] = {};
  bool active_[kRayLanes] = {};
  volume::Lighting<float> light_[kRayLanes] = {};
};

}  // namespace

bool raymarch_lanes_apply(const RaymarchLayout& c) {
  return (c.bits & (kRayLerp | kRayPreintegrate)) == 0u;
}

void pad_volume(const double* volume, UVec3 dims, uint32_t z_begin, uint32_t z_end, float* padded) {
  const size_t px = dims.x + 1u, py = dims.y + 1u;
  for (uint32_t k = z_begin; k < z_end; ++k) {
    const uint32_t ks = hd::min_t(k, dims.z - 1u);
    for (uint32_t j = 0; j < py; ++j) {
      const double* row = volume + (size_t(ks) * dims.y + hd::min_t(j, dims.y - 1u)) * dims.x;
      float* out = padded + (size_t(k) * py + j) * px;
      for (uint32_t i = 0; i < dims.x; ++i) out[i] = float(row[i]);
      out[dims.x] = float(row[dims.x - 1u]);
    }
  }
}

void raymarch_lanes(const RaymarchLayout& c, const float* volume, const hd::V4<float>* tf,
                    const hd::V4<float>* bricks, uint64_t begin, uint64_t end, double* image) {
  LaneMarch(c, volume, tf, bricks, image).run(begin, end);
}

}  // namespace masav::cpu
