#version 450
#extension GL_GOOGLE_include_directive : require
// grid_rank_in_cell, and each point's two 4-vectors and id move with it to their sorted slot:
// the gathers of a simulation's re-sort folded into the rank pass. Twin of
// KernelBody<grid_rank_and_move> (engine/kernels/grid_body.h).
#include "kernel_base.glsl"
#include "engine/kernels/grid_params.h"

// What the kernel only reads are uniform texel buffers (compute/vk_kernels.cpp): lavapipe fetches
// a texel with a gather, where it loads a storage buffer's element in a loop over the lanes.
layout(binding = 1) uniform usamplerBuffer cell_texels;        // r32ui
layout(binding = 2) uniform usamplerBuffer unsorted_texels;    // r32ui
layout(binding = 3) uniform usamplerBuffer cell_start_texels;  // r32ui
layout(binding = 4) uniform usamplerBuffer cell_end_texels;    // r32ui
uint cell_at(uint i) { return texelFetch(cell_texels, int(i)).r; }
uint unsorted_at(uint s) { return texelFetch(unsorted_texels, int(s)).r; }
uint cell_start_at(uint c) { return texelFetch(cell_start_texels, int(c)).r; }
uint cell_end_at(uint c) { return texelFetch(cell_end_texels, int(c)).r; }
layout(std430, binding = 5) writeonly buffer SortedCells { uint sorted_cells[]; };
layout(std430, binding = 6) writeonly buffer SortedIndex { uint sorted_index[]; };
layout(binding = 7) uniform samplerBuffer a_texels;  // rgba32f
layout(std430, binding = 8) writeonly buffer ASorted { vec4 a_sorted[]; };
layout(binding = 9) uniform samplerBuffer b_texels;  // rgba32f
layout(std430, binding = 10) writeonly buffer BSorted { vec4 b_sorted[]; };
layout(binding = 11) uniform usamplerBuffer id_texels;  // r32ui
layout(std430, binding = 12) writeonly buffer IdsSorted { uint ids_sorted[]; };
MASAV_PUSH(CellRankParams);

#include "grid_rank.glsl"

void run() {
  const uint s = flat_invocation_id();
  if (s >= p.n) return;
  uint i, c, d;
  if (!rank_slot(s, kDiagMoveOutsideCell, kDiagMoveCellOverfull, i, c, d)) return;
  sorted_cells[d] = c;
  sorted_index[d] = i;
  a_sorted[d] = texelFetch(a_texels, int(i));
  b_sorted[d] = texelFetch(b_texels, int(i));
  ids_sorted[d] = texelFetch(id_texels, int(i)).r;
}

void main() {
  MASAV_LOAD_PUSH();
  run();
  report_loop_ticks();
}
