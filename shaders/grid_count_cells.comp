#version 450
#extension GL_GOOGLE_include_directive : require
// counts[cells[i]] += 1 for i < n: the first pass of a counting sort by cell. Integer atomics,
// so the counts are the same in any order. Twin of KernelBody<grid_count_cells>
// (engine/kernels/grid_body.h).
#include "kernel_base.glsl"
#include "engine/kernels/grid_params.h"

layout(std430, binding = 1) readonly buffer Cells { uint cells[]; };
layout(std430, binding = 2) buffer Counts { uint counts[]; };
MASAV_PUSH(CellCountParams);

void run() {
  const uint i = flat_invocation_id();
  if (i >= p.n) return;
  const uint c = cells[i];
  if (c >= p.cell_count) {
    report_diagnostic(kDiagCellOutOfRange, i);
    return;
  }
  atomicAdd(counts[c], 1u);
}

void main() {
  MASAV_LOAD_PUSH();
  run();
  report_loop_ticks();
}
