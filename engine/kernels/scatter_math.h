#pragma once
// One photon of scatter_table (thesis §2.2.3, [Magnor 2005]), shared by the CPU reference
// (T = double) and CUDA (T = float); shaders/common/scatter.glsl is the GLSL twin.
//
// The sphere has radius l = 1, so sigma_sct = tau. Per event k the photon uses Philox block k of
// its own stream (three uniforms: free path, HG cos theta, azimuth), so every backend draws the
// same photons; paths differ between backends only by float rounding.
#include <cstdint>

#include "engine/kernels/atom_params.h"
#include "engine/kernels/hd_vec.h"
#include "engine/kernels/philox.h"

namespace masav::scatter {

constexpr double kPi = 3.14159265358979323846;
constexpr uint32_t kFixedShift = 20;  // GPU tallies: weight * 2^20 as integers (see below)

// Henyey-Greenstein: cos theta for a uniform v in [0, 1) (thesis formula; isotropic for g ~ 0).
template <class T>
MASAV_HD inline T hg_cos_theta(T g, T v) {
  if (hd::abs_t(g) < T(1e-6)) return T(2) * v - T(1);
  const T q = (T(1) - g * g) / (T(1) - g + T(2) * g * v);
  return hd::clamp_t((T(1) + g * g - q * q) / (T(2) * g), T(-1), T(1));
}

// New direction at angle theta (cos_theta) from d, azimuth phi about d. The thesis's update
// [Magnor 2005] with one sign fixed: its d'_y term "- d_x sin(phi)" must be "+ d_x sin(phi)"
// (as in MCML, Wang et al. 1995), else d' is not a unit vector at angle theta from d. Near the
// z axis (|d_z| > 0.9999) the thesis's special case. Renormalised against rounding drift.
template <class T>
MASAV_HD inline hd::V3<T> scatter_direction(hd::V3<T> d, T cos_theta, T phi) {
  const T st = hd::sqrt_t(hd::max_t(T(0), T(1) - cos_theta * cos_theta));
  const T cp = hd::cos_t(phi), sp = hd::sin_t(phi);
  if (hd::abs_t(d.z) > T(0.9999))
    return hd::V3<T>{st * cp, st * sp, (d.z > T(0) ? T(1) : T(-1)) * cos_theta};
  const T zeta = hd::sqrt_t(T(1) - d.z * d.z);
  const hd::V3<T> n{st / zeta * (d.x * d.z * cp - d.y * sp) + d.x * cos_theta,
                    st / zeta * (d.y * d.z * cp + d.x * sp) + d.y * cos_theta,
                    -zeta * st * cp + d.z * cos_theta};
  return hd::normalize(n);
}

// Distance from x (inside the unit sphere) along unit d to the sphere.
template <class T>
MASAV_HD inline T sphere_exit(hd::V3<T> x, hd::V3<T> d) {
  const T b = hd::dot(x, d), c = hd::dot(x, x) - T(1);
  return -b + hd::sqrt_t(hd::max_t(T(0), b * b - c));
}

template <class T>
struct Outcome {
  uint32_t entry;        // bin, or bins + kScatterCapped / kScatterThreshold
  uint32_t scatterings;  // events before the outcome
  T weight;
};

template <class T>
MASAV_HD inline uint32_t cos_bin(T mu, uint32_t bins) {
  const T x = (hd::clamp_t(mu, T(-1), T(1)) + T(1)) * (T(bins) * T(0.5));
  const uint32_t b = uint32_t(x);
  return b < bins ? b : bins - 1u;
}

// The photon's life: escape (its weight lands in the bin of cos(angle to d0)), weight below the
// threshold after a scattering (dropped), or a (max_scatterings + 1)-th scattering (capped).
// The free path r = -ln(1 - u) / tau is compared as an optical length (-ln(1 - u) against
// tau * distance to the sphere) so that tau = 0 needs no division: the photon leaves unscattered.
template <class T>
MASAV_HD inline Outcome<T> trace_photon(const ScatterTableParams& p, T tau, uint64_t stream) {
  const hd::V3<T> d0 =
      hd::normalize(hd::V3<T>{T(p.direction.x), T(p.direction.y), T(p.direction.z)});
  hd::V3<T> x = p.start == ScatterStart::centre ? hd::V3<T>{T(0), T(0), T(0)} : d0 * T(-1);
  hd::V3<T> d = d0;
  T w = T(1);
  for (uint32_t k = 0; k <= p.max_scatterings; ++k) {
    const philox::Block b = philox::stream_block(p.seed, stream, k);
    const T optical = -hd::log_t(T(1) - T(philox::u01(b.w[0])));
    if (optical >= tau * sphere_exit(x, d))
      return Outcome<T>{cos_bin(hd::dot(d, d0), p.bins), k, w};
    if (k == p.max_scatterings) return Outcome<T>{p.bins + kScatterCapped, k, w};
    x = x + d * (optical / tau);
    w *= T(p.albedo);
    if (w < T(p.weight_threshold)) return Outcome<T>{p.bins + kScatterThreshold, k + 1, w};
    const T ct = hg_cos_theta(T(p.g), T(philox::u01(b.w[1])));
    d = scatter_direction(d, ct, T(2) * T(kPi) * T(philox::u01(b.w[2])));
  }
  return Outcome<T>{p.bins + kScatterCapped, p.max_scatterings, w};  // not reached
}

MASAV_HD inline uint64_t photon_stream(const ScatterTableParams& p, uint32_t row_in_call,
                                       uint32_t photon) {
  return kScatterStream + uint64_t(p.first_row + row_in_call) * p.photons_per_row + photon;
}

// Fixed-point weight for the GPU tallies (integer atomics add up in any order to the same sum):
// 2^-20 resolution, rounded to nearest; 1024 photons of weight 1 fit a 32-bit shared counter.
template <class T>
MASAV_HD inline uint32_t fixed_weight(T w) {
  return uint32_t(w * T(1u << kFixedShift) + T(0.5));
}

}  // namespace masav::scatter
