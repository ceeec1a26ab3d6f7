// dst[i] = src[order[i]]; an index past the source writes zero and reports it. ELEM_T is the
// element's word type (uint or uvec4), set by the including kernel.
#include "kernel_base.glsl"
#include "engine/kernels/grid_params.h"

layout(std430, binding = 1) readonly buffer Order { uint order[]; };
layout(std430, binding = 2) readonly buffer Src { ELEM_T src[]; };
layout(std430, binding = 3) writeonly buffer Dst { ELEM_T dst[]; };
MASAV_PUSH(GatherLayout);

void run() {
  const uint i = flat_invocation_id();
  if (i >= p.n) return;
  const uint j = order[i];
  if (j >= p.src_count) {
    dst[i] = ELEM_T(0u);
    report_diagnostic(kDiagGatherIndexOutOfRange, i);
    return;
  }
  dst[i] = src[j];
}

void main() {
  run();
  report_loop_ticks();
}
