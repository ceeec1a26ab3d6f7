#version 450
#extension GL_GOOGLE_include_directive : require
// cells[i] = grid cell of positions[i] (clamped to the box) and counts[cells[i]] += 1, for
// i < n: grid_assign_cells and the first pass of the counting sort in one dispatch. Integer
// atomics, so the counts are the same in any order. Twin of KernelBody<grid_assign_count>
// (engine/kernels/grid_body.h).
#include "kernel_base.glsl"
#include "grid_cell.glsl"
#include "engine/kernels/grid_params.h"

// The positions are a uniform texel buffer (compute/vk_kernels.cpp): lavapipe loads a storage
// buffer's element in a loop over the lanes.
layout(binding = 1) uniform samplerBuffer position_texels;  // rgba32f
layout(std430, binding = 2) writeonly buffer Cells { uint cells[]; };
layout(std430, binding = 3) buffer Counts { uint counts[]; };
MASAV_PUSH(CellAssignCountParams);

void run() {
  const uint i = flat_invocation_id();
  if (i >= p.grid.n) return;
  const uvec3 c = grid_point_cell(texelFetch(position_texels, int(i)).xyz, p.grid.origin, p.grid.inv_cell, p.grid.dims);
  const uint cell = grid_cell_id(c, p.grid.dims);
  cells[i] = cell;
  atomicAdd(counts[cell], 1u);
}

void main() {
  MASAV_LOAD_PUSH();
  run();
  report_loop_ticks();
}
