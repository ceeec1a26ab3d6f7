#version 450
#extension GL_GOOGLE_include_directive : require
// The fourth pass of the counting sort by cell: the point in slot s moves to its cell's start
// plus the number of its cell's points with a smaller index, so each run is in increasing index
// (the stable radix sort's order). The loop runs over the cell, at most max_per_cell points
// (validated below the loop limit). Twin of KernelBody<grid_rank_in_cell>
// (engine/kernels/grid_body.h).
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
  MASAV_LOAD_PUSH();
  run();
  report_loop_ticks();
}
