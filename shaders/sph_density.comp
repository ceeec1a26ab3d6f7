#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_arithmetic : require
// Density (poly6, thesis Eq. 4.4) and pressure of each sorted particle over the neighbours
// within h in the 27 cells around cells[i], walked as 9 rows of 3 consecutive cells. The
// candidates per invocation are capped (max_candidates) and an overflow is reported, never
// silently truncated. Twin of sph::density_at (engine/kernels/sph_kernels.h).
#include "kernel_base.glsl"

layout(std430, binding = 1) readonly buffer Positions { vec4 positions[]; };
layout(std430, binding = 2) readonly buffer Cells { uint cells[]; };
layout(std430, binding = 3) readonly buffer Start { uint cell_start[]; };
layout(std430, binding = 4) readonly buffer End { uint cell_end[]; };
layout(std430, binding = 5) writeonly buffer Density { float density[]; };
layout(std430, binding = 6) writeonly buffer Pressure { float pressure[]; };
layout(std430, binding = 7) buffer Stats { uint stats[]; };

#include "sph.glsl"
#include "sph_walk.glsl"

MASAV_PUSH(SphStepLayout);

void main() {
  const uint i = flat_invocation_id();
  const bool live = i < p.n;
  uint candidates = 0u, within = 0u;
  bool overflow = false, bad = false;
  if (live) {
    const vec3 xi = positions[i].xyz;
    const uvec3 dims = p.dims;
    const ivec3 cc = sph_cell_coords(cells[i], dims);
    float sum = 0.0;
    for (int dx = -1; dx <= 1 && !overflow; ++dx) {
      LOOP_TICK();
      const int x = cc.x + dx;
      if (x < 0 || x >= int(dims.x)) continue;
      for (int dy = -1; dy <= 1; ++dy) {
        LOOP_TICK();
        const int y = cc.y + dy;
        if (y < 0 || y >= int(dims.y)) continue;
        const uvec2 r = sph_row_range(x, y, cc.z, dims);
        if (r.y - r.x > p.max_candidates - candidates) {
          overflow = true;
          break;
        }
        candidates += r.y - r.x;
        for (uint j = r.x; j < r.y; ++j) {
          LOOP_TICK();
          const vec3 d = xi - positions[j].xyz;
          const float r2 = dot(d, d);
          sum += sph_density_term(r2, p);
          within += r2 < p.h2 ? 1u : 0u;
        }
      }
    }
    float rho = p.density * sum;
    if (p.walls != 0u) {
      vec3 unused;
      rho += p.rest_density * sph_wall_density(xi, p, unused);
    }
    const float pr = sph_pressure_of(rho, p);
    density[i] = rho;
    pressure[i] = pr;
    bad = !sph_finite(rho) || !sph_finite(pr);
  }
  // One atomic per subgroup and statistic.
  const uint max_cand = subgroupMax(candidates);
  const uint max_within = subgroupMax(within);
  const uint over = subgroupMax(overflow ? ~i : 0u);
  const uint nonfinite = subgroupMax(bad ? ~i : 0u);
  if (subgroupElect()) {
    atomicMax(stats[kSphStatMaxCandidates], max_cand);
    atomicMax(stats[kSphStatMaxNeighbors], max_within);
    if (over != 0u) atomicMax(stats[kSphStatOverflow], over);
    if (nonfinite != 0u) atomicMax(stats[kSphStatNonFinite], nonfinite);
  }
  report_loop_ticks();
}
