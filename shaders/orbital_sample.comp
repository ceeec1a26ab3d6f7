#version 450
#extension GL_GOOGLE_include_directive : require
// orbital_sample: particle i from Philox block i of the orbital stream, by inverting the
// |psi|^2 factor tables (exact placement) or by site search and jitter (shell placement).
// Twin of orbital::sample_particle (engine/kernels/orbital_math.h).
#include "kernel_base.glsl"
#include "philox.glsl"
#include "engine/kernels/atom_params.h"

layout(std430, binding = 1) readonly buffer Tables { uint tables[]; };
layout(std430, binding = 2) writeonly buffer Positions { vec4 positions[]; };
MASAV_PUSH(OrbitalSampleParams);

#include "orbital.glsl"

float u01f(uint w) { return philox_u01(w); }

void run() {
  const uint i = flat_invocation_id();
  if (i >= p.count) return;
  const uvec4 b = philox_stream_block(p.seed, kOrbitalStream, uvec2(i, 0u), 0u);
  vec3 x;
  if (p.placement == OrbitalPlacement_shells) {
    const uint sites = p.radial_bins * p.polar_bins * p.azimuth_bins;
    const uint site = cdf_search(0u, sites, i);
    const uint ir = site / (p.polar_bins * p.azimuth_bins);
    const uint it = (site / p.azimuth_bins) % p.polar_bins, ip = site % p.azimuth_bins;
    const float dr = p.radial_max_a0 / float(p.radial_bins);
    const float r0 = float(ir) * dr, r1 = r0 + dr;
    const float r = pow(r0 * r0 * r0 + u01f(b.x) * (r1 * r1 * r1 - r0 * r0 * r0), 1.0 / 3.0);
    const float ct = -1.0 + (float(it) + u01f(b.y)) * (2.0 / float(p.polar_bins));
    const float phi = (float(ip) + u01f(b.z)) * (2.0 * ORBITAL_PI / float(p.azimuth_bins));
    x = spherical_to_cartesian(r, ct, phi);
  } else {
    const uint polar = p.radial_bins + 1u, azimuth = polar + p.polar_bins + 1u;
    const float r = cdf_invert(0u, p.radial_bins, b.x >> 8, 0.0, p.radial_max_a0);
    const float ct = cdf_invert(polar, p.polar_bins, b.y >> 8, -1.0, 2.0);
    float phi;
    if (p.azimuth_bins == 0u) {
      phi = 2.0 * ORBITAL_PI * u01f(b.z);
    } else {
      const float psi = cdf_invert(azimuth, p.azimuth_bins, b.z >> 8, 0.0, ORBITAL_PI);
      const uint k = ((b.w >> 8) * p.azimuth_periods) >> 24;
      phi = (float(k) * ORBITAL_PI + psi + p.azimuth_offset) / float(p.azimuth_periods / 2u);
    }
    x = spherical_to_cartesian(r, ct, phi);
  }
  positions[i] = vec4(x, 0.0);
}

void main() {
  MASAV_LOAD_PUSH();
  run();
  report_loop_ticks();
}
