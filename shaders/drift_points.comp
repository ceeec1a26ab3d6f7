#version 450
#extension GL_GOOGLE_include_directive : require
// positions[i] = the periodic drift of point i at time_s (engine/kernels/drift_params.h);
// positions[i].w = its speed. One point per invocation, no loops. Twin of
// KernelBody<drift_points> (engine/kernels/drift_body.h).
#include "kernel_base.glsl"
#include "drift.glsl"
#include "engine/kernels/drift_params.h"

layout(std430, binding = 1) readonly buffer Start { vec4 start_u[]; };
layout(std430, binding = 2) readonly buffer Direction { vec4 dir_u[]; };
layout(std430, binding = 3) writeonly buffer Positions { vec4 positions[]; };
MASAV_PUSH(DriftParams);

void run() {
  const uint i = flat_invocation_id();
  if (i >= p.n) return;
  const vec4 u = start_u[i], w = dir_u[i];
  precise float speed_t = p.speed * p.time_s;
  precise vec4 x;
  precise float v2 = 0.0;
  for (int a = 0; a < 3; ++a) {
    LOOP_TICK();
    x[a] = p.box_lo[a] + p.box_extent[a] * drift_axis_fraction(u[a], w[a], speed_t);
    const float v = drift_axis_velocity(w[a], p.speed, p.box_extent[a]);
    v2 += v * v;
  }
  x.w = sqrt(v2);
  positions[i] = x;
}

void main() {
  MASAV_LOAD_PUSH();
  run();
  report_loop_ticks();
}
