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

void run() {
  const uint s = flat_invocation_id();
  if (s >= p.n) return;
  const uint i = unsorted[s];
  const uint c = i < p.n ? cells[i] : p.cell_count;
  if (c >= p.cell_count || s < cell_start[c] || s >= cell_end[c] || cell_end[c] > p.n) {
    report_diagnostic(kDiagRankOutsideCell, s);
    return;
  }
  const uint first = cell_start[c], last = cell_end[c];
  if (last - first > p.max_per_cell) {
    report_diagnostic(kDiagCellOverfull, c);
    return;
  }
  uint rank = 0u;
  for (uint t = first; t < last; ++t) {
    LOOP_TICK();
    rank += unsorted[t] < i ? 1u : 0u;
  }
  sorted_cells[first + rank] = c;
  sorted_index[first + rank] = i;
}

void main() {
  run();
  report_loop_ticks();
}
