#version 450
#extension GL_GOOGLE_include_directive : require
// Radix sort pass, step 3 of 3: each workgroup sorts its tile stably by the pass's digit in
// shared memory (2-bit splits, each one workgroup scan), then writes every element to
// offset[digit][tile] + its rank among the tile's elements of that digit.
#include "kernel_base.glsl"
#include "engine/kernels/sort_params.h"
#include "workgroup_scan.glsl"
#include "radix.glsl"

layout(constant_id = kSpecItems) const uint ITEMS = 8u;
layout(constant_id = kSpecHasValues) const bool HAS_VALUES = true;
const uint TILE = WG_SIZE * ITEMS;  // < 65536: split counts are packed in 16-bit fields

layout(std430, binding = 1) readonly buffer KeysIn { uint keys_in[]; };
layout(std430, binding = 2) readonly buffer ValsIn { uint vals_in[]; };
layout(std430, binding = 3) writeonly buffer KeysOut { uint keys_out[]; };
layout(std430, binding = 4) writeonly buffer ValsOut { uint vals_out[]; };
layout(std430, binding = 5) readonly buffer Offsets { uint offsets[]; };
MASAV_PUSH(RadixPassParams);

shared uint s_keys[TILE];
shared uint s_vals[TILE];
shared uint s_digit_start[256];

// One count in the 16-bit field of a 2-bit sub-digit: (sd0 | sd1 << 16, sd2 | sd3 << 16).
uvec2 split_one(uint sd) { return uvec2(sd == 0u ? 1u : (sd == 1u ? 65536u : 0u),
                                        sd == 2u ? 1u : (sd == 3u ? 65536u : 0u)); }

void run() {
  const uint tile = flat_group_id();
  if (tile >= p.num_tiles) return;  // whole workgroup leaves together
  const uint lid = gl_LocalInvocationID.x;
  const uint base = tile * TILE;
  const uint valid = min(TILE, p.n - base);
  const uint rank = wg_rank();

  // Coalesced load; padding keys of all ones sort after every real key (the sort is stable
  // and padding sits at the end of the tile).
  for (uint i = 0u; i < ITEMS; ++i) {
    LOOP_TICK();
    const uint pos = i * WG_SIZE + lid;
    s_keys[pos] = pos < valid ? keys_in[base + pos] : 0xFFFFFFFFu;
    if (HAS_VALUES) s_vals[pos] = pos < valid ? vals_in[base + pos] : 0u;
  }
  barrier();
  uint k[ITEMS];
  uint v[ITEMS];
  for (uint i = 0u; i < ITEMS; ++i) {
    LOOP_TICK();
    k[i] = s_keys[rank * ITEMS + i];
    v[i] = HAS_VALUES ? s_vals[rank * ITEMS + i] : 0u;
  }

  for (uint b = 0u; b < p.bits; b += 2u) {
    LOOP_TICK();
    const uint sh = p.shift + b;
    const uint mask = p.bits - b >= 2u ? 3u : 1u;
    uvec2 count = uvec2(0u);
    for (uint i = 0u; i < ITEMS; ++i) {
      LOOP_TICK();
      count += split_one((k[i] >> sh) & mask);
    }
    uvec2 total;
    const uvec2 before = wg_exclusive_scan2(count, total);  // ends with a barrier
    uint run_pos[4] = uint[4](before.x & 0xFFFFu, before.x >> 16, before.y & 0xFFFFu,
                              before.y >> 16);
    const uint t0 = total.x & 0xFFFFu, t1 = total.x >> 16, t2 = total.y & 0xFFFFu;
    const uint start[4] = uint[4](0u, t0, t0 + t1, t0 + t1 + t2);
    for (uint i = 0u; i < ITEMS; ++i) {
      LOOP_TICK();
      const uint sd = (k[i] >> sh) & mask;
      const uint pos = start[sd] + run_pos[sd];
      run_pos[sd] += 1u;
      s_keys[pos] = k[i];
      if (HAS_VALUES) s_vals[pos] = v[i];
    }
    barrier();
    for (uint i = 0u; i < ITEMS; ++i) {
      LOOP_TICK();
      k[i] = s_keys[rank * ITEMS + i];
      if (HAS_VALUES) v[i] = s_vals[rank * ITEMS + i];
    }
  }

  // First position of each digit present in the sorted tile.
  for (uint i = 0u; i < ITEMS; ++i) {
    LOOP_TICK();
    const uint pos = rank * ITEMS + i;
    if (pos < valid) {
      const uint d = radix_digit(k[i], p.shift, p.bits);
      if (pos == 0u || radix_digit(s_keys[pos - 1u], p.shift, p.bits) != d) s_digit_start[d] = pos;
    }
  }
  barrier();
  for (uint i = 0u; i < ITEMS; ++i) {
    LOOP_TICK();
    const uint pos = i * WG_SIZE + lid;
    if (pos < valid) {
      const uint key = s_keys[pos];
      const uint d = radix_digit(key, p.shift, p.bits);
      const uint dst = offsets[d * p.num_tiles + tile] + (pos - s_digit_start[d]);
      keys_out[dst] = key;
      if (HAS_VALUES) vals_out[dst] = s_vals[pos];
    }
  }
}

void main() {
  MASAV_LOAD_PUSH();
  run();
  report_loop_ticks();
}
