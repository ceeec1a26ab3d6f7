#version 450
#extension GL_GOOGLE_include_directive : require
// Exclusive prefix sum, fix-up step: adds each tile's scanned offset to its elements.
#include "kernel_base.glsl"
#include "engine/kernels/sort_params.h"

layout(constant_id = kSpecItems) const uint ITEMS = 8u;
const uint TILE = WG_SIZE * ITEMS;

layout(std430, binding = 1) buffer Data { uint data[]; };
layout(std430, binding = 2) readonly buffer Sums { uint sums[]; };
MASAV_PUSH(ScanParams);

void run() {
  const uint tile = flat_group_id();
  if (tile >= p.num_tiles) return;
  const uint add = sums[tile];
  const uint base = tile * TILE;
  for (uint i = 0u; i < ITEMS; ++i) {
    LOOP_TICK();
    const uint pos = base + i * WG_SIZE + gl_LocalInvocationID.x;
    if (pos < p.n) data[pos] += add;
  }
}

void main() {
  MASAV_LOAD_PUSH();
  run();
  report_loop_ticks();
}
