#version 450
#extension GL_GOOGLE_include_directive : require
// cells[i] = grid cell of positions[i] (thesis Eq. 4.1-4.2, clamped to the box), indices[i] = i.
#include "kernel_base.glsl"
#include "grid_cell.glsl"

layout(std430, binding = 1) readonly buffer Positions { vec4 positions[]; };
layout(std430, binding = 2) writeonly buffer Cells { uint cells[]; };
layout(std430, binding = 3) writeonly buffer Indices { uint indices[]; };
layout(push_constant) uniform Push {
  vec4 origin_inv_cell;  // xyz origin, w 1/cell_size
  uvec4 dims_n;          // xyz dims, w point count
} pc;

void run() {
  const uint i = flat_invocation_id();
  if (i >= pc.dims_n.w) return;
  const uvec3 c = grid_point_cell(positions[i].xyz, pc.origin_inv_cell.xyz, pc.origin_inv_cell.w,
                                  pc.dims_n.xyz);
  cells[i] = grid_cell_id(c, pc.dims_n.xyz);
  indices[i] = i;
}

void main() {
  run();
  report_loop_ticks();
}
