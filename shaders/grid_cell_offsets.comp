#version 450
#extension GL_GOOGLE_include_directive : require
// The scan step of grid_cell_offsets (compute/vk_grid.cpp): chunk k's kCellOffsetChunk counts
// scanned one by one from the chunk's offset (the exclusive scan of the chunk sums), writing both
// ends of each cell's run: cell_start[c] = counts before c, cell_end[c] = cell_start[c] +
// counts[c].
#include "kernel_base.glsl"
#include "engine/kernels/grid_params.h"
#include "engine/kernels/sort_params.h"

layout(std430, binding = 1) readonly buffer Counts { uint counts[]; };
layout(std430, binding = 2) readonly buffer Offsets { uint chunk_offsets[]; };
layout(std430, binding = 3) writeonly buffer Start { uint cell_start[]; };
layout(std430, binding = 4) writeonly buffer End { uint cell_end[]; };
MASAV_PUSH(ScanParams);  // n: cells, num_tiles: chunks

void run() {
  const uint chunk = flat_invocation_id();
  if (chunk >= p.num_tiles) return;
  const uint base = chunk * kCellOffsetChunk;
  const uint size = min(kCellOffsetChunk, p.n - base);
  uint at = chunk_offsets[chunk];
  for (uint i = 0u; i < size; ++i) {
    LOOP_TICK();
    cell_start[base + i] = at;
    at += counts[base + i];
    cell_end[base + i] = at;
  }
}

void main() {
  MASAV_LOAD_PUSH();
  run();
  report_loop_ticks();
}
