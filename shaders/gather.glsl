// dst[i] = src[order[i]]; an index past the source writes zero and reports it. ELEM_T is the
// element's word type (uint or uvec4), set by the including kernel. order and src are uniform
// texel buffers (r32ui, and r32ui or rgba32ui: compute/vk_grid.cpp), which lavapipe reads with
// gathers or plain loads, where it loads a storage buffer's element in a loop over the lanes.
#include "kernel_base.glsl"
#include "engine/kernels/grid_params.h"

layout(binding = 1) uniform usamplerBuffer order_texels;
layout(binding = 2) uniform usamplerBuffer src_texels;
layout(std430, binding = 3) writeonly buffer Dst { ELEM_T dst[]; };
MASAV_PUSH(GatherLayout);

void run() {
  const uint i = flat_invocation_id();
  if (i >= p.n) return;
  const uint j = texelFetch(order_texels, int(i)).r;
  if (j >= p.src_count) {
    dst[i] = ELEM_T(0u);
    report_diagnostic(kDiagGatherIndexOutOfRange, i);
    return;
  }
  dst[i] = ELEM_T(texelFetch(src_texels, int(j)));
}

void main() {
  MASAV_LOAD_PUSH();
  run();
  report_loop_ticks();
}
