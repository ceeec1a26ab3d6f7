#version 450
#extension GL_GOOGLE_include_directive : require
// Exclusive prefix sum, fix-up step where there are at most TILE tiles: each workgroup adds up
// the totals of the tiles before its own (sums[0..tile): scan_tiles' per-tile totals, not
// scanned) and adds that offset to its elements. One dispatch where scanning the totals and
// then adding them takes two; integer sums, so the result is the same in any order.
#include "kernel_base.glsl"
#include "engine/kernels/sort_params.h"

layout(constant_id = kSpecItems) const uint ITEMS = 8u;
const uint TILE = WG_SIZE * ITEMS;

layout(std430, binding = 1) buffer Data { uint data[]; };
layout(std430, binding = 2) readonly buffer Sums { uint sums[]; };
MASAV_PUSH(ScanParams);

shared uint partial[WG_SIZE];

void run() {
  const uint tile = flat_group_id();
  if (tile >= p.num_tiles) return;  // the whole workgroup: no barrier is left waiting
  const uint lid = gl_LocalInvocationID.x;
  uint s = 0u;
  for (uint k = lid; k < tile; k += WG_SIZE) {  // at most ITEMS passes (num_tiles <= TILE)
    LOOP_TICK();
    s += sums[k];
  }
  partial[lid] = s;
  barrier();
  uint width = 1u;  // the power of two at or above WG_SIZE (a multiple of 64, not always 2^k)
  while (width < WG_SIZE) {
    LOOP_TICK();
    width <<= 1u;
  }
  for (uint stride = width >> 1u; stride > 0u; stride >>= 1u) {
    LOOP_TICK();
    if (lid < stride && lid + stride < WG_SIZE) partial[lid] += partial[lid + stride];
    barrier();
  }
  const uint add = partial[0];
  const uint base = tile * TILE;
  for (uint i = 0u; i < ITEMS; ++i) {
    LOOP_TICK();
    const uint pos = base + i * WG_SIZE + lid;
    if (pos < p.n) data[pos] += add;
  }
}

void main() {
  MASAV_LOAD_PUSH();
  run();
  report_loop_ticks();
}
