#version 450
#extension GL_GOOGLE_include_directive : require
// orbital_sample: particle i from Philox block i of the orbital stream, by inverting the
// |psi|^2 factor tables (exact placement) or by site search and jitter (shell placement).
// Twin of orbital::sample_particle (engine/kernels/orbital_math.h).
#include "kernel_base.glsl"
#include "philox.glsl"

layout(std430, binding = 1) readonly buffer Tables { uint tables[]; };
layout(std430, binding = 2) writeonly buffer Positions { vec4 positions[]; };
layout(push_constant) uniform Push {
  uint count;
  uint placement;  // 0 exact, 1 shells
  uvec2 seed;
  uint radial_bins, polar_bins, azimuth_bins, azimuth_periods;
  float radial_max, azimuth_offset;
} pc;

#include "orbital.glsl"

const uvec2 ORBITAL_STREAM = uvec2(0x00000001u, 0x0A700000u);  // kOrbitalStream

float u01f(uint w) { return philox_u01(w); }

void run() {
  const uint i = flat_invocation_id();
  if (i >= pc.count) return;
  const uvec4 b = philox_stream_block(pc.seed, ORBITAL_STREAM, uvec2(i, 0u), 0u);
  vec3 x;
  if (pc.placement == 1u) {
    const uint sites = pc.radial_bins * pc.polar_bins * pc.azimuth_bins;
    const uint site = cdf_search(0u, sites, i);
    const uint ir = site / (pc.polar_bins * pc.azimuth_bins);
    const uint it = (site / pc.azimuth_bins) % pc.polar_bins, ip = site % pc.azimuth_bins;
    const float dr = pc.radial_max / float(pc.radial_bins);
    const float r0 = float(ir) * dr, r1 = r0 + dr;
    const float r = pow(r0 * r0 * r0 + u01f(b.x) * (r1 * r1 * r1 - r0 * r0 * r0), 1.0 / 3.0);
    const float ct = -1.0 + (float(it) + u01f(b.y)) * (2.0 / float(pc.polar_bins));
    const float phi = (float(ip) + u01f(b.z)) * (2.0 * ORBITAL_PI / float(pc.azimuth_bins));
    x = spherical_to_cartesian(r, ct, phi);
  } else {
    const uint polar = pc.radial_bins + 1u, azimuth = polar + pc.polar_bins + 1u;
    const float r = cdf_invert(0u, pc.radial_bins, b.x >> 8, 0.0, pc.radial_max);
    const float ct = cdf_invert(polar, pc.polar_bins, b.y >> 8, -1.0, 2.0);
    float phi;
    if (pc.azimuth_bins == 0u) {
      phi = 2.0 * ORBITAL_PI * u01f(b.z);
    } else {
      const float psi = cdf_invert(azimuth, pc.azimuth_bins, b.z >> 8, 0.0, ORBITAL_PI);
      const uint k = ((b.w >> 8) * pc.azimuth_periods) >> 24;
      phi = (float(k) * ORBITAL_PI + psi + pc.azimuth_offset) / float(pc.azimuth_periods / 2u);
    }
    x = spherical_to_cartesian(r, ct, phi);
  }
  positions[i] = vec4(x, 0.0);
}

void main() {
  run();
  report_loop_ticks();
}
