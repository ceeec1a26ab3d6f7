#version 450
#extension GL_GOOGLE_include_directive : require
// Marks where each cell's run of sorted points begins and ends; cell_start and cell_end are
// cleared to 0 beforehand, so empty cells read as the empty range [0, 0).
#include "kernel_base.glsl"
#include "engine/kernels/grid_params.h"

layout(std430, binding = 1) readonly buffer Cells { uint cells[]; };
layout(std430, binding = 2) writeonly buffer Start { uint cell_start[]; };
layout(std430, binding = 3) writeonly buffer End { uint cell_end[]; };
MASAV_PUSH(GridParams);

void run() {
  const uint i = flat_invocation_id();
  if (i >= p.n) return;
  const uint c = cells[i];
  if (i == 0u || cells[i - 1u] != c) cell_start[c] = i;
  if (i + 1u == p.n || cells[i + 1u] != c) cell_end[c] = i + 1u;
}

void main() {
  MASAV_LOAD_PUSH();
  run();
  report_loop_ticks();
}
