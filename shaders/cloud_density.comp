#version 450
#extension GL_GOOGLE_include_directive : require
// density[c] = (cell_end[c] - cell_start[c]) * scale, scale = 1 / (particles * cell^3).
#include "kernel_base.glsl"

layout(std430, binding = 1) readonly buffer Start { uint cell_start[]; };
layout(std430, binding = 2) readonly buffer End { uint cell_end[]; };
layout(std430, binding = 3) writeonly buffer Density { float density[]; };
layout(push_constant) uniform Push {
  uint cells;
  float scale;
} pc;

void main() {
  const uint c = flat_invocation_id();
  if (c < pc.cells) density[c] = float(cell_end[c] - cell_start[c]) * pc.scale;
  report_loop_ticks();
}
