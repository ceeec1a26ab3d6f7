#version 450
#extension GL_GOOGLE_include_directive : require
// Radix sort pass, step 1 of 3: per-tile digit counts, written digit-major
// (hist[digit * num_tiles + tile]) so that one exclusive scan of hist gives every tile's output
// offset for every digit (reduce-then-scan: no workgroup waits on another).
#include "kernel_base.glsl"
#include "engine/kernels/sort_params.h"
#include "radix.glsl"

layout(constant_id = kSpecItems) const uint ITEMS = 8u;
const uint TILE = WG_SIZE * ITEMS;

layout(std430, binding = 1) readonly buffer Keys { uint keys[]; };
layout(std430, binding = 2) writeonly buffer Hist { uint hist[]; };
MASAV_PUSH(RadixPassParams);

shared uint s_hist[256];

void run() {
  const uint tile = flat_group_id();
  if (tile >= p.num_tiles) return;  // whole workgroup leaves together
  const uint lid = gl_LocalInvocationID.x;
  const uint radix = 1u << p.bits;
  for (uint d = lid; d < radix; d += WG_SIZE) {
    LOOP_TICK();
    s_hist[d] = 0u;
  }
  barrier();
  const uint base = tile * TILE;
  for (uint i = 0u; i < ITEMS; ++i) {
    LOOP_TICK();
    const uint idx = base + i * WG_SIZE + lid;
    if (idx < p.n) atomicAdd(s_hist[radix_digit(keys[idx], p.shift, p.bits)], 1u);
  }
  barrier();
  for (uint d = lid; d < radix; d += WG_SIZE) {
    LOOP_TICK();
    hist[d * p.num_tiles + tile] = s_hist[d];
  }
}

void main() {
  MASAV_LOAD_PUSH();
  run();
  report_loop_ticks();
}
