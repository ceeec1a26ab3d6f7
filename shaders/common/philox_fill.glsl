// philox_u32 and philox_uniform: one 4-word block per invocation, of the stream PhiloxLayout
// names (engine/kernels/random_params.h). The including shader defines PHILOX_WORD(w), what a
// word becomes (itself, or its uniform float's bits). Twin of KernelBody<philox_*>
// (engine/kernels/philox.h).
#include "kernel_base.glsl"
#include "philox.glsl"
#include "engine/kernels/random_params.h"

layout(std430, binding = 1) writeonly buffer Out { uint out_words[]; };
MASAV_PUSH(PhiloxLayout);

void run() {
  const uint block = flat_invocation_id();
  if (block >= (p.count + 3u) / 4u) return;
  const uvec4 r = philox_stream_block(p.seed, p.stream, p.first_block, block);
  for (uint j = 0u; j < 4u; ++j) {
    LOOP_TICK();
    const uint i = 4u * block + j;
    if (i < p.count) out_words[i] = PHILOX_WORD(r[j]);
  }
}

void main() {
  MASAV_LOAD_PUSH();
  run();
  report_loop_ticks();
}
