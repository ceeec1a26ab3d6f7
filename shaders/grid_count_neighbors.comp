#version 450
#extension GL_GOOGLE_include_directive : require
// counts[i] = sorted points within radius of sorted point i over its 27 cells. The candidate
// count per invocation is capped (max_candidates) to stay under lavapipe's loop limit; a point
// over the cap is reported instead of silently miscounted.
#include "kernel_base.glsl"
#include "grid_cell.glsl"
#include "engine/kernels/grid_params.h"

// What the kernel only reads are uniform texel buffers (compute/vk_kernels.cpp): lavapipe fetches
// a texel with a gather, where it loads a storage buffer's element in a loop over the lanes.
layout(binding = 1) uniform samplerBuffer position_texels;     // rgba32f
layout(binding = 2) uniform usamplerBuffer cell_start_texels;  // r32ui
layout(binding = 3) uniform usamplerBuffer cell_end_texels;    // r32ui
vec3 position_at(uint i) { return texelFetch(position_texels, int(i)).xyz; }
layout(std430, binding = 4) writeonly buffer Counts { uint counts[]; };
MASAV_PUSH(NeighborParams);

void run() {
  const uint i = flat_invocation_id();
  if (i >= p.grid.n) return;
  const vec3 x = position_at(i);
  const uvec3 c = grid_point_cell(x, p.grid.origin, p.grid.inv_cell, p.grid.dims);
  uint count = 0u, candidates = 0u;
  bool over = false;
  for (int k = 0; k < 27 && !over; ++k) {
    LOOP_TICK();
    uint id;
    if (!grid_neighbor_cell(c, p.grid.dims, k, id)) continue;
    const uint last = texelFetch(cell_end_texels, int(id)).r;
    for (uint j = texelFetch(cell_start_texels, int(id)).r; j < last; ++j) {
      LOOP_TICK();
      if (++candidates > p.max_candidates) {
        over = true;
        break;
      }
      if (grid_distance2(x, position_at(j)) <= p.radius2) ++count;
    }
  }
  counts[i] = count;
  if (over) report_diagnostic(kDiagNeighborOverflow, i);
}

void main() {
  MASAV_LOAD_PUSH();
  run();
  report_loop_ticks();
}
