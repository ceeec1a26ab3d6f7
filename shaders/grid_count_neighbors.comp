#version 450
#extension GL_GOOGLE_include_directive : require
// counts[i] = sorted points within radius of sorted point i over its 27 cells. The candidate
// count per invocation is capped (max_candidates) to stay under lavapipe's loop limit; a point
// over the cap is reported instead of silently miscounted.
#include "kernel_base.glsl"
#include "grid_cell.glsl"

layout(std430, binding = 1) readonly buffer Positions { vec4 positions[]; };
layout(std430, binding = 2) readonly buffer Start { uint cell_start[]; };
layout(std430, binding = 3) readonly buffer End { uint cell_end[]; };
layout(std430, binding = 4) writeonly buffer Counts { uint counts[]; };
layout(push_constant) uniform Push {
  vec4 origin_inv_cell;
  uvec4 dims_n;
  float radius2;
  uint max_candidates;
} pc;

void run() {
  const uint i = flat_invocation_id();
  if (i >= pc.dims_n.w) return;
  const vec3 p = positions[i].xyz;
  const uvec3 c = grid_point_cell(p, pc.origin_inv_cell.xyz, pc.origin_inv_cell.w, pc.dims_n.xyz);
  uint count = 0u, candidates = 0u;
  bool over = false;
  for (int k = 0; k < 27 && !over; ++k) {
    LOOP_TICK();
    uint id;
    if (!grid_neighbor_cell(c, pc.dims_n.xyz, k, id)) continue;
    const uint last = cell_end[id];
    for (uint j = cell_start[id]; j < last; ++j) {
      LOOP_TICK();
      if (++candidates > pc.max_candidates) {
        over = true;
        break;
      }
      if (grid_distance2(p, positions[j].xyz) <= pc.radius2) ++count;
    }
  }
  counts[i] = count;
  if (over) report_diagnostic(DIAG_NEIGHBOR_OVERFLOW, i);
}

void main() {
  run();
  report_loop_ticks();
}
