#version 450
#extension GL_GOOGLE_include_directive : require
// grid_rank_in_cell, and each point's two 4-vectors and id move with it to their sorted slot:
// the gathers of a simulation's re-sort folded into the rank pass. Twin of
// KernelBody<grid_rank_and_move> (engine/kernels/grid_body.h).
#include "kernel_base.glsl"
#include "engine/kernels/grid_params.h"

layout(std430, binding = 1) readonly buffer Cells { uint cells[]; };
layout(std430, binding = 2) readonly buffer Unsorted { uint unsorted[]; };
layout(std430, binding = 3) readonly buffer Start { uint cell_start[]; };
layout(std430, binding = 4) readonly buffer End { uint cell_end[]; };
layout(std430, binding = 5) writeonly buffer SortedCells { uint sorted_cells[]; };
layout(std430, binding = 6) writeonly buffer SortedIndex { uint sorted_index[]; };
layout(std430, binding = 7) readonly buffer A { vec4 a[]; };
layout(std430, binding = 8) writeonly buffer ASorted { vec4 a_sorted[]; };
layout(std430, binding = 9) readonly buffer B { vec4 b[]; };
layout(std430, binding = 10) writeonly buffer BSorted { vec4 b_sorted[]; };
layout(std430, binding = 11) readonly buffer Ids { uint ids[]; };
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
  a_sorted[d] = a[i];
  b_sorted[d] = b[i];
  ids_sorted[d] = ids[i];
}

void main() {
  run();
  report_loop_ticks();
}
