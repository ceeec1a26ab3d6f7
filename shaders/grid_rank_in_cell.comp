#version 450
#extension GL_GOOGLE_include_directive : require
// The fourth pass of the counting sort by cell: the point in slot s moves to its cell's start
// plus the number of its cell's points with a smaller index, so each run is in increasing index
// (the stable radix sort's order). The loop runs over the cell, at most max_per_cell points
// (validated below the loop limit). Twin of KernelBody<grid_rank_in_cell>
// (engine/kernels/grid_body.h).
#include "kernel_base.glsl"
#include "engine/kernels/grid_params.h"

layout(std430, binding = 1) readonly buffer Cells { uint cells[]; };
layout(std430, binding = 2) readonly buffer Unsorted { uint unsorted[]; };
layout(std430, binding = 3) readonly buffer Start { uint cell_start[]; };
layout(std430, binding = 4) readonly buffer End { uint cell_end[]; };
layout(std430, binding = 5) writeonly buffer SortedCells { uint sorted_cells[]; };
layout(std430, binding = 6) writeonly buffer SortedIndex { uint sorted_index[]; };
MASAV_PUSH(CellRankParams);

#include "grid_rank.glsl"

void run() {
  const uint s = flat_invocation_id();
  if (s >= p.n) return;
  uint i, c, d;
  if (!rank_slot(s, kDiagRankOutsideCell, kDiagCellOverfull, i, c, d)) return;
  sorted_cells[d] = c;
  sorted_index[d] = i;
}

void main() {
  run();
  report_loop_ticks();
}
