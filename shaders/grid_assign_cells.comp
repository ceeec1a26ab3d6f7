#version 450
#extension GL_GOOGLE_include_directive : require
// cells[i] = grid cell of positions[i] (thesis Eq. 4.1-4.2, clamped to the box), indices[i] = i.
// Twin of KernelBody<grid_assign_cells> (engine/kernels/grid_body.h).
#include "kernel_base.glsl"
#include "grid_cell.glsl"
#include "engine/kernels/grid_params.h"

layout(std430, binding = 1) readonly buffer Positions { vec4 positions[]; };
layout(std430, binding = 2) writeonly buffer Cells { uint cells[]; };
layout(std430, binding = 3) writeonly buffer Indices { uint indices[]; };
MASAV_PUSH(GridParams);

void run() {
  const uint i = flat_invocation_id();
  if (i >= p.n) return;
  const uvec3 c = grid_point_cell(positions[i].xyz, p.origin, p.inv_cell, p.dims);
  cells[i] = grid_cell_id(c, p.dims);
  indices[i] = i;
}

void main() {
  MASAV_LOAD_PUSH();
  run();
  report_loop_ticks();
}
