#version 450
#extension GL_GOOGLE_include_directive : require
// Philox words or uniform floats: one 4-word block per invocation.
#include "kernel_base.glsl"
#include "philox.glsl"

layout(constant_id = 3) const bool UNIFORM_FLOATS = false;

layout(std430, binding = 1) writeonly buffer Out { uint out_words[]; };
layout(push_constant) uniform Push {
  uvec2 seed;
  uvec2 stream;
  uvec2 first_block;
  uint count;
} pc;

void run() {
  const uint block = flat_invocation_id();
  if (block >= (pc.count + 3u) / 4u) return;
  const uvec4 r = philox_stream_block(pc.seed, pc.stream, pc.first_block, block);
  for (uint j = 0u; j < 4u; ++j) {
    LOOP_TICK();
    const uint i = 4u * block + j;
    if (i < pc.count) out_words[i] = UNIFORM_FLOATS ? floatBitsToUint(philox_u01(r[j])) : r[j];
  }
}

void main() {
  run();
  report_loop_ticks();
}
