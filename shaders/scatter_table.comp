#version 450
#extension GL_GOOGLE_include_directive : require
// scatter_table: one photon per invocation; every workgroup serves one tau row. Tallies go to
// shared memory as fixed-point integers (2^-20 of a unit weight), then once per workgroup to the
// row's 64-bit tallies (lo word with carry into hi): integer sums, so the order of the atomics
// does not change the result.
#include "kernel_base.glsl"
#include "philox.glsl"
#include "scatter.glsl"

layout(constant_id = 3) const uint ENTRIES = 75u;  // bins + 3 extras

layout(std430, binding = 1) buffer Tallies { uint tallies[]; };  // (lo, hi) per row and entry
layout(std430, binding = 2) buffer Hits { uint hits[]; };
layout(push_constant) uniform Push {
  uint rows, first_row, bins, photons_per_row;
  uint groups_per_row, max_scatterings, from_centre, pad;
  vec4 dir_tau_step;  // d0.xyz, tau_step
  float g, albedo, threshold, pad2;
  uvec2 seed;
} pc;

shared uint s_weight[ENTRIES];
shared uint s_hits[ENTRIES];

const uvec2 SCATTER_STREAM = uvec2(0u, 0x5CA70000u);  // kScatterStream

uvec2 add64(uvec2 a, uvec2 b) {
  uint carry;
  const uint lo = uaddCarry(a.x, b.x, carry);
  return uvec2(lo, a.y + b.y + carry);
}

void main() {
  const uint lid = gl_LocalInvocationID.x;
  for (uint e = lid; e < ENTRIES; e += WG_SIZE) {
    LOOP_TICK();
    s_weight[e] = 0u;
    s_hits[e] = 0u;
  }
  barrier();
  const uint group = flat_group_id();
  const uint row = group / pc.groups_per_row;
  const uint photon = (group % pc.groups_per_row) * WG_SIZE + lid;
  if (row < pc.rows && photon < pc.photons_per_row) {
    PhotonSetup s;
    s.d0 = normalize(pc.dir_tau_step.xyz);
    s.from_centre = pc.from_centre != 0u;
    s.g = pc.g;
    s.albedo = pc.albedo;
    s.threshold = pc.threshold;
    s.max_scatterings = pc.max_scatterings;
    s.bins = pc.bins;
    s.seed = pc.seed;
    uvec2 prod;
    umulExtended(pc.first_row + row, pc.photons_per_row, prod.y, prod.x);
    const uvec2 stream = add64(add64(SCATTER_STREAM, prod), uvec2(photon, 0u));
    const float tau = float(pc.first_row + row) * pc.dir_tau_step.w;
    const PhotonOutcome o = trace_photon(s, tau, stream);
    const uint fw = fixed_weight(o.weight);
    atomicAdd(s_weight[o.entry], fw);
    atomicAdd(s_hits[o.entry], 1u);
    if (o.entry < pc.bins && o.scatterings == 0u) {
      atomicAdd(s_weight[pc.bins + SCATTER_UNSCATTERED], fw);
      atomicAdd(s_hits[pc.bins + SCATTER_UNSCATTERED], 1u);
    }
  }
  barrier();
  if (row < pc.rows) {
    for (uint e = lid; e < ENTRIES; e += WG_SIZE) {
      LOOP_TICK();
      const uint n = s_hits[e];
      if (n == 0u) continue;
      const uint w = s_weight[e];
      const uint slot = row * ENTRIES + e;
      const uint old = atomicAdd(tallies[2u * slot], w);
      if (old + w < old) atomicAdd(tallies[2u * slot + 1u], 1u);
      atomicAdd(hits[slot], n);
    }
  }
  report_loop_ticks();
}
