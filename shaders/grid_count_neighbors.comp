#version 450
#extension GL_GOOGLE_include_directive : require
// counts[i] = sorted points within radius of sorted point i over its 27 cells. The candidate
// count per invocation is capped (max_candidates) to stay under lavapipe's loop limit; a point
// over the cap is reported instead of silently miscounted.
#include "kernel_base.glsl"
#include "grid_cell.glsl"
#include "engine/kernels/grid_params.h"

layout(std430, binding = 1) readonly buffer Positions { vec4 positions[]; };
layout(std430, binding = 2) readonly buffer Start { uint cell_start[]; };
layout(std430, binding = 3) readonly buffer End { uint cell_end[]; };
layout(std430, binding = 4) writeonly buffer Counts { uint counts[]; };
MASAV_PUSH(NeighborParams);

void run() {
  const uint i = flat_invocation_id();
  if (i >= p.grid.n) return;
  const vec3 x = positions[i].xyz;
  const uvec3 c = grid_point_cell(x, p.grid.origin, p.grid.inv_cell, p.grid.dims);
  uint count = 0u, candidates = 0u;
  bool over = false;
  for (int k = 0; k < 27 && !over; ++k) {
    LOOP_TICK();
    uint id;
    if (!grid_neighbor_cell(c, p.grid.dims, k, id)) continue;
    const uint last = cell_end[id];
    for (uint j = cell_start[id]; j < last; ++j) {
      LOOP_TICK();
      if (++candidates > p.max_candidates) {
        over = true;
        break;
      }
      if (grid_distance2(x, positions[j].xyz) <= p.radius2) ++count;
    }
  }
  counts[i] = count;
  if (over) report_diagnostic(kDiagNeighborOverflow, i);
}

void main() {
  run();
  report_loop_ticks();
}
