#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_ballot : require
// Radix sort pass, step 3 of 3, for CPU-like devices (lavapipe): one subgroup is the whole
// workgroup and walks its tile in order, SUBGROUP keys per round. Keys of equal digit in a round
// are found with one ballot per digit bit, ranked by their lane, and placed after the digit's
// running count (s_next). About one shared-memory access per key, where the tiled scatter needs
// about thirty; lavapipe executes each such access lane by lane.
// Precondition (checked by the host): the workgroup is exactly one full subgroup.
#include "kernel_base.glsl"
#include "engine/kernels/sort_params.h"
#include "radix.glsl"

layout(constant_id = kSpecItems) const uint ITEMS = 256u;  // rounds per tile
layout(constant_id = kSpecHasValues) const bool HAS_VALUES = true;
const uint TILE = WG_SIZE * ITEMS;

layout(std430, binding = 1) readonly buffer KeysIn { uint keys_in[]; };
layout(std430, binding = 2) readonly buffer ValsIn { uint vals_in[]; };
layout(std430, binding = 3) writeonly buffer KeysOut { uint keys_out[]; };
layout(std430, binding = 4) writeonly buffer ValsOut { uint vals_out[]; };
layout(std430, binding = 5) readonly buffer Offsets { uint offsets[]; };
MASAV_PUSH(RadixPassParams);

shared uint s_next[256];  // next output position of each digit in this tile

uint count_bits(uvec4 m) { return bitCount(m.x) + bitCount(m.y) + bitCount(m.z) + bitCount(m.w); }

void run() {
  const uint tile = flat_group_id();
  if (tile >= p.num_tiles) return;
  const uint lane = gl_SubgroupInvocationID;
  const uint radix = 1u << p.bits;
  for (uint d = lane; d < radix; d += WG_SIZE) {
    LOOP_TICK();
    s_next[d] = offsets[d * p.num_tiles + tile];
  }
  barrier();
  const uint base = tile * TILE;
  for (uint r = 0u; r < ITEMS; ++r) {
    LOOP_TICK();
    const uint idx = base + r * WG_SIZE + lane;  // lane order = index order within a round
    const bool valid = idx < p.n;
    const uint key = valid ? keys_in[idx] : 0u;
    const uint d = radix_digit(key, p.shift, p.bits);
    uvec4 same = subgroupBallot(valid);
    for (uint b = 0u; b < p.bits; ++b) {
      LOOP_TICK();
      const bool set = ((d >> b) & 1u) != 0u;
      const uvec4 ones = subgroupBallot(set);
      same &= set ? ones : ~ones;
    }
    const uint rank = count_bits(same & gl_SubgroupLtMask);
    const uint count = count_bits(same);
    const uint first = s_next[d];
    // The workgroup is one subgroup, so subgroup barriers order it (a workgroup barrier costs
    // lavapipe a coroutine switch): every lane reads s_next before the digit's last lane moves it.
    subgroupMemoryBarrierShared();
    subgroupBarrier();
    if (valid) {
      const uint dst = first + rank;
      keys_out[dst] = key;
      if (HAS_VALUES) vals_out[dst] = vals_in[idx];
      if (rank + 1u == count) s_next[d] = first + count;
    }
    subgroupMemoryBarrierShared();
    subgroupBarrier();
  }
}

void main() {
  MASAV_LOAD_PUSH();
  run();
  report_loop_ticks();
}
