#version 450
#extension GL_GOOGLE_include_directive : require
// The reduce step of grid_cell_offsets (compute/vk_grid.cpp): sums[k] = the total of the
// kCellOffsetChunk consecutive counts of chunk k, one invocation per chunk.
#include "kernel_base.glsl"
#include "engine/kernels/grid_params.h"
#include "engine/kernels/sort_params.h"

layout(std430, binding = 1) readonly buffer Counts { uint counts[]; };
layout(std430, binding = 2) writeonly buffer Sums { uint sums[]; };
MASAV_PUSH(ScanParams);  // n: cells, num_tiles: chunks

void run() {
  const uint chunk = flat_invocation_id();
  if (chunk >= p.num_tiles) return;
  const uint base = chunk * kCellOffsetChunk;
  const uint size = min(kCellOffsetChunk, p.n - base);
  uint sum = 0u;
  for (uint i = 0u; i < size; ++i) {
    LOOP_TICK();
    sum += counts[base + i];
  }
  sums[chunk] = sum;
}

void main() {
  MASAV_LOAD_PUSH();
  run();
  report_loop_ticks();
}
