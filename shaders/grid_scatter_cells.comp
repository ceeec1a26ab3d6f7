#version 450
#extension GL_GOOGLE_include_directive : require
// The third pass of the counting sort by cell: point i takes slot cell_end[c] - counts[c] and
// counts its cell down by one, so the cell's points fill its run in arrival order and the count
// table ends all zero. Twin of KernelBody<grid_scatter_cells> (engine/kernels/grid_body.h).
#include "kernel_base.glsl"
#include "engine/kernels/grid_params.h"

// What the kernel only reads are uniform texel buffers (compute/vk_kernels.cpp): lavapipe fetches
// a texel with a gather, where it loads a storage buffer's element in a loop over the lanes.
layout(binding = 1) uniform usamplerBuffer cell_texels;      // r32ui
layout(binding = 2) uniform usamplerBuffer cell_end_texels;  // r32ui
layout(std430, binding = 3) buffer Counts { uint counts[]; };
layout(std430, binding = 4) writeonly buffer Unsorted { uint unsorted[]; };
MASAV_PUSH(CellScatterParams);

void run() {
  const uint i = flat_invocation_id();
  if (i >= p.n) return;
  const uint c = texelFetch(cell_texels, int(i)).r;
  if (c >= p.cell_count) {
    report_diagnostic(kDiagScatterNoSlot, i);
    return;
  }
  const uint left = atomicAdd(counts[c], 0xFFFFFFFFu);
  if (left == 0u) {  // no slot left: undo, so the table stays as it was
    atomicAdd(counts[c], 1u);
    report_diagnostic(kDiagScatterNoSlot, i);
    return;
  }
  const uint end = texelFetch(cell_end_texels, int(c)).r;
  if (left > end || end > p.n) {  // the slot end - left would lie outside [0, n)
    report_diagnostic(kDiagScatterNoSlot, i);
    return;
  }
  unsorted[end - left] = i;
}

void main() {
  MASAV_LOAD_PUSH();
  run();
  report_loop_ticks();
}
