#version 450
#extension GL_GOOGLE_include_directive : require
// Exclusive prefix sum, level step: each workgroup scans one tile in place and writes the
// tile's total to sums[tile]; the host scans the sums (recursively) and scan_add adds them back.
#include "kernel_base.glsl"
#include "engine/kernels/sort_params.h"
#include "workgroup_scan.glsl"

layout(constant_id = kSpecItems) const uint ITEMS = 8u;
const uint TILE = WG_SIZE * ITEMS;

layout(std430, binding = 1) buffer Data { uint data[]; };
layout(std430, binding = 2) writeonly buffer Sums { uint sums[]; };
MASAV_PUSH(ScanParams);

shared uint s_data[TILE];

void run() {
  const uint tile = flat_group_id();
  if (tile >= p.num_tiles) return;
  const uint lid = gl_LocalInvocationID.x;
  const uint base = tile * TILE;
  const uint valid = min(TILE, p.n - base);
  const uint rank = wg_rank();
  for (uint i = 0u; i < ITEMS; ++i) {
    LOOP_TICK();
    const uint pos = i * WG_SIZE + lid;
    s_data[pos] = pos < valid ? data[base + pos] : 0u;
  }
  barrier();
  uint x[ITEMS];
  uint sum = 0u;
  for (uint i = 0u; i < ITEMS; ++i) {
    LOOP_TICK();
    x[i] = s_data[rank * ITEMS + i];
    sum += x[i];
  }
  uint total;
  uint prefix = wg_exclusive_scan(sum, total);  // ends with a barrier
  for (uint i = 0u; i < ITEMS; ++i) {
    LOOP_TICK();
    s_data[rank * ITEMS + i] = prefix;
    prefix += x[i];
  }
  barrier();
  for (uint i = 0u; i < ITEMS; ++i) {
    LOOP_TICK();
    const uint pos = i * WG_SIZE + lid;
    if (pos < valid) data[base + pos] = s_data[pos];
  }
  if (lid == 0u) sums[tile] = total;
}

void main() {
  MASAV_LOAD_PUSH();
  run();
  report_loop_ticks();
}
