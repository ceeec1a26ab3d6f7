#pragma once
// orbital_sample's per-particle body, shared by the CPU reference (T = double) and CUDA
// (T = float); shaders/common/orbital.glsl is the GLSL twin. Table construction and its error
// analysis: engine/atom/orbital_tables.h.
#include <cstdint>

#include "engine/kernels/atom_params.h"
#include "engine/kernels/hd_vec.h"
#include "engine/kernels/philox.h"

namespace masav::orbital {

constexpr double kPi = 3.14159265358979323846;

// The largest k in [0, bins) with cdf[k] <= u, for cdf[0] <= u < cdf[bins]: at most 32 halvings,
// integer compares only, so every backend picks the same bin.
MASAV_HD inline uint32_t cdf_search(const uint32_t* cdf, uint32_t bins, uint32_t u) {
  uint32_t lo = 0, hi = bins;
  for (int it = 0; it < 32 && hi - lo > 1u; ++it) {
    const uint32_t mid = (lo + hi) >> 1;
    if (cdf[mid] <= u)
      lo = mid;
    else
      hi = mid;
  }
  return lo;
}

// Inverse CDF of a table over [x0, x0 + range) with `bins` equal bins: the bin holding the 24-bit
// uniform u, then the point that splits the bin's mass as u does (flat density inside a bin).
template <class T>
MASAV_HD inline T cdf_invert(const uint32_t* cdf, uint32_t bins, uint32_t u, T x0, T range) {
  const uint32_t k = cdf_search(cdf, bins, u);
  const uint32_t lo = cdf[k], hi = cdf[k + 1];
  const T t = (T(u - lo) + T(0.5)) / T(hi - lo);
  return x0 + (T(k) + t) * (range / T(bins));
}

template <class T>
MASAV_HD inline hd::V3<T> spherical_to_cartesian(T r, T cos_theta, T phi) {
  const T sin_theta = hd::sqrt_t(hd::max_t(T(0), T(1) - cos_theta * cos_theta));
  return {r * sin_theta * hd::cos_t(phi), r * sin_theta * hd::sin_t(phi), r * cos_theta};
}

template <class T>
MASAV_HD inline T u01(uint32_t word) {
  return T(philox::u01(word));
}

// Particle i: exact placement draws (r, cos theta, phi) from the three tables with the four words
// of Philox block i; shell placement finds the site holding particle i in the cumulative counts
// and jitters uniformly in the site's volume.
template <class T>
MASAV_HD inline hd::V3<T> sample_particle(const OrbitalSampleParams& p, const uint32_t* cdf,
                                          uint32_t i) {
  const philox::Block b = philox::stream_block(p.seed, kOrbitalStream, i);
  const T pi = T(kPi);
  if (p.placement == OrbitalPlacement::shells) {
    const uint32_t sites = p.radial_bins * p.polar_bins * p.azimuth_bins;
    const uint32_t site = cdf_search(cdf, sites, i);
    const uint32_t ir = site / (p.polar_bins * p.azimuth_bins);
    const uint32_t it = (site / p.azimuth_bins) % p.polar_bins, ip = site % p.azimuth_bins;
    const T dr = T(p.radial_max_a0) / T(p.radial_bins);
    const T r0 = T(ir) * dr, r1 = r0 + dr;
    const T r = hd::cbrt_t(r0 * r0 * r0 + u01<T>(b.w[0]) * (r1 * r1 * r1 - r0 * r0 * r0));
    const T ct = T(-1) + (T(it) + u01<T>(b.w[1])) * (T(2) / T(p.polar_bins));
    const T phi = (T(ip) + u01<T>(b.w[2])) * (T(2) * pi / T(p.azimuth_bins));
    return spherical_to_cartesian(r, ct, phi);
  }
  const uint32_t* radial = cdf;
  const uint32_t* polar = radial + p.radial_bins + 1;
  const uint32_t* azimuth = polar + p.polar_bins + 1;
  const T r = cdf_invert<T>(radial, p.radial_bins, b.w[0] >> 8, T(0), T(p.radial_max_a0));
  const T ct = cdf_invert<T>(polar, p.polar_bins, b.w[1] >> 8, T(-1), T(2));
  T phi;
  if (p.azimuth_bins == 0) {
    phi = T(2) * pi * u01<T>(b.w[2]);
  } else {
    // cos^2(|m| phi) repeats 2|m| times in [0, 2 pi): a period k (exact multiply-shift of 24
    // bits; periods <= 256 keeps it in 32 bits), then psi in [0, pi) from the cos^2 table.
    const T psi = cdf_invert<T>(azimuth, p.azimuth_bins, b.w[2] >> 8, T(0), pi);
    const uint32_t k = ((b.w[3] >> 8) * p.azimuth_periods) >> 24;
    phi = (T(k) * pi + psi + T(p.azimuth_offset)) / T(p.azimuth_periods / 2);
  }
  return spherical_to_cartesian(r, ct, phi);
}

}  // namespace masav::orbital
