#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_KHR_shader_subgroup_shuffle : require
// Acceleration of each sorted particle: pressure (spiky gradient) and viscosity (its laplacian)
// per the pressure model, times the inverse mass (positions' w), plus gravity. One invocation
// per particle, no atomics in the neighbour loop, neighbours walked cooperatively
// (sph_coop.glsl) with p / rho^2 computed once per loaded candidate. Twin of sph::force_at
// (engine/kernels/sph_kernels.h).
#include "kernel_base.glsl"

layout(std430, binding = 1) readonly buffer Positions { vec4 positions[]; };
layout(std430, binding = 2) readonly buffer Velocities { vec4 velocities[]; };
layout(std430, binding = 3) readonly buffer Density { float density[]; };
layout(std430, binding = 4) readonly buffer Pressure { float pressure[]; };
layout(std430, binding = 5) readonly buffer Cells { uint cells[]; };
layout(std430, binding = 6) readonly buffer Start { uint cell_start[]; };
layout(std430, binding = 7) readonly buffer End { uint cell_end[]; };
layout(std430, binding = 8) writeonly buffer Accel { vec4 accel[]; };
layout(std430, binding = 9) buffer Stats { uint stats[]; };

#include "sph.glsl"
#include "sph_walk.glsl"
#include "sph_coop.glsl"

MASAV_PUSH(SphStepLayout);

void main() {
  const uint i = flat_invocation_id();
  const bool live = i < p.n;
  uint candidates = 0u;
  bool overflow = false, bad = false;
  float accel2 = 0.0;
  // Every lane runs the row loops (see sph_coop.glsl); dead lanes have empty rows.
  vec4 pw = vec4(0.0);
  vec3 v = vec3(0.0);
  float rho = 1.0, pi_over_rho2 = 0.0;
  ivec3 cc = ivec3(-4);
  if (live) {
    pw = positions[i];
    v = velocities[i].xyz;
    rho = density[i];
    pi_over_rho2 = pressure[i] / (rho * rho);
    cc = sph_cell_coords(cells[i], p.dims);
  }
  const vec3 xi = pw.xyz;
  const uvec3 dims = p.dims;
  uint spent = 0u;
  vec3 acc = vec3(0.0);
  uint neighbors = 0u;
  for (int dx = -1; dx <= 1; ++dx) {
    LOOP_TICK();
    for (int dy = -1; dy <= 1; ++dy) {
      LOOP_TICK();
      const int x = cc.x + dx, y = cc.y + dy;
      uvec2 r = uvec2(0u);
      if (live && !overflow && x >= 0 && x < int(dims.x) && y >= 0 && y < int(dims.y)) {
        r = sph_row_range(x, y, cc.z, dims);
        if (r.y - r.x > p.max_candidates - candidates) {
          overflow = true;
          r = uvec2(0u);
        }
        candidates += r.y - r.x;
      }
      uvec2 u;
      if (sph_coop_row(r, spent, u)) {
        for (uint base = u.x; base < u.y; base += kSphCoop) {
          LOOP_TICK();
          // One candidate per lane: position, velocity, density and p / rho^2.
          const uint mine = base + sph_coop_lane();
          vec3 xc = vec3(0.0), vc = vec3(0.0);
          float rc = 1.0, qc = 0.0;
          if (mine < u.y) {
            xc = positions[mine].xyz;
            vc = velocities[mine].xyz;
            rc = density[mine];
            qc = pressure[mine] / (rc * rc);
          }
          for (uint k = 0u; k < kSphCoop; ++k) {
            LOOP_TICK();
            const uint src = sph_coop_source(k);
            const vec3 xj = subgroupShuffle(xc, src);
            const vec3 vj = subgroupShuffle(vc, src);
            const float rho_j = subgroupShuffle(rc, src);
            const float q_j = subgroupShuffle(qc, src);
            const uint j = base + ((sph_coop_lane() + k) & (kSphCoop - 1u));
            const vec3 d = xi - xj;
            const float r2 = dot(d, d);
            if (j >= r.x && j < r.y && j != i && r2 < p.h2) {
              ++neighbors;
              acc += sph_pair_accel(v, rho, pi_over_rho2, vj, rho_j, q_j, d, r2, p);
            }
          }
        }
      } else {
        for (uint j = r.x; j < r.y; ++j) {
          LOOP_TICK();
          if (j == i) continue;
          const vec3 d = xi - positions[j].xyz;
          const float r2 = dot(d, d);
          if (!(r2 < p.h2)) continue;
          ++neighbors;
          const float rho_j = density[j];
          acc += sph_pair_accel(v, rho, pi_over_rho2, velocities[j].xyz, rho_j,
                                pressure[j] / (rho_j * rho_j), d, r2, p);
        }
      }
    }
  }
  if (live) {
    if (p.walls != 0u) {
      vec3 n;
      sph_wall_density(xi, p, n);
      const float damp = p.wall_viscosity * (2.0 * p.rest_density / (rho + p.rest_density)) *
                         sph_wall_viscous_weight(xi, p);
      acc += (2.0 * pi_over_rho2 * p.rest_density * p.inv_h) * n - damp * v;
    }
    const vec3 a = sph_total_accel(acc, pw.w, p);
    accel[i] = vec4(a, float(neighbors));
    bad = !sph_finite(a);
    if (!bad && pw.w > 0.0) accel2 = dot(a, a);
  }
  const uint max_cand = subgroupMax(candidates);
  const uint over = subgroupMax(overflow ? ~i : 0u);
  const uint nonfinite = subgroupMax(bad ? ~i : 0u);
  const uint max_a2 = subgroupMax(floatBitsToUint(accel2));
  if (subgroupElect()) {
    atomicMax(stats[kSphStatMaxCandidates], max_cand);
    atomicMax(stats[kSphStatMaxAccel2], max_a2);
    if (over != 0u) atomicMax(stats[kSphStatOverflow], over);
    if (nonfinite != 0u) atomicMax(stats[kSphStatNonFinite], nonfinite);
  }
  report_loop_ticks();
}
