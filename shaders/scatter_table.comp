#version 450
#extension GL_GOOGLE_include_directive : require
// scatter_table: one photon per invocation; every workgroup serves one tau row. Tallies go to
// shared memory as fixed-point integers (2^-20 of a unit weight), then once per workgroup to the
// row's 64-bit tallies (lo word with carry into hi): integer sums, so the order of the atomics
// does not change the result.
#include "kernel_base.glsl"
#include "philox.glsl"
#include "engine/kernels/atom_params.h"
#include "scatter.glsl"

layout(constant_id = kSpecScatterEntries) const uint ENTRIES = 75u;  // bins + 3 extras

layout(std430, binding = 1) buffer Tallies { uint tallies[]; };  // (lo, hi) per row and entry
layout(std430, binding = 2) buffer Hits { uint hits[]; };
MASAV_PUSH(ScatterTableParams);

shared uint s_weight[ENTRIES];
shared uint s_hits[ENTRIES];

uvec2 add64(uvec2 a, uvec2 b) {
  uint carry;
  const uint lo = uaddCarry(a.x, b.x, carry);
  return uvec2(lo, a.y + b.y + carry);
}

void main() {
  MASAV_LOAD_PUSH();
  const uint lid = gl_LocalInvocationID.x;
  for (uint e = lid; e < ENTRIES; e += WG_SIZE) {
    LOOP_TICK();
    s_weight[e] = 0u;
    s_hits[e] = 0u;
  }
  barrier();
  const uint group = flat_group_id();
  const uint groups_per_row = (p.photons_per_row + WG_SIZE - 1u) / WG_SIZE;
  const uint row = group / groups_per_row;
  const uint photon = (group % groups_per_row) * WG_SIZE + lid;
  if (row < p.rows && photon < p.photons_per_row) {
    PhotonSetup s;
    s.d0 = normalize(p.direction);
    s.from_centre = p.start == ScatterStart_centre;
    s.g = p.g;
    s.albedo = p.albedo;
    s.threshold = p.weight_threshold;
    s.max_scatterings = p.max_scatterings;
    s.bins = p.bins;
    s.seed = p.seed;
    uvec2 prod;
    umulExtended(p.first_row + row, p.photons_per_row, prod.y, prod.x);
    const uvec2 stream = add64(add64(kScatterStream, prod), uvec2(photon, 0u));
    const float tau = float(p.first_row + row) * p.tau_step;
    const PhotonOutcome o = trace_photon(s, tau, stream);
    const uint fw = fixed_weight(o.weight);
    atomicAdd(s_weight[o.entry], fw);
    atomicAdd(s_hits[o.entry], 1u);
    if (o.entry < p.bins && o.scatterings == 0u) {
      atomicAdd(s_weight[p.bins + kScatterUnscattered], fw);
      atomicAdd(s_hits[p.bins + kScatterUnscattered], 1u);
    }
  }
  barrier();
  if (row < p.rows) {
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
