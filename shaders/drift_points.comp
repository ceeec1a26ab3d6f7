#version 450
#extension GL_GOOGLE_include_directive : require
// positions[i] = the periodic drift of point i at time_s (engine/points/drift_params.h);
// positions[i].w = its speed. One point per invocation, no loops.
#include "kernel_base.glsl"
#include "drift.glsl"

layout(std430, binding = 1) readonly buffer Start { vec4 start_u[]; };
layout(std430, binding = 2) readonly buffer Direction { vec4 dir_u[]; };
layout(std430, binding = 3) writeonly buffer Positions { vec4 positions[]; };
layout(push_constant) uniform Push {
  vec4 lo_speed;     // box_lo, speed
  vec4 extent_time;  // box_extent, time_s
  uint n;
} pc;

void run() {
  const uint i = flat_invocation_id();
  if (i >= pc.n) return;
  const vec4 u = start_u[i], w = dir_u[i];
  precise float speed_t = pc.lo_speed.w * pc.extent_time.w;
  precise vec4 p;
  precise float v2 = 0.0;
  for (int a = 0; a < 3; ++a) {
    LOOP_TICK();
    p[a] = pc.lo_speed[a] + pc.extent_time[a] * drift_axis_fraction(u[a], w[a], speed_t);
    const float v = drift_axis_velocity(w[a], pc.lo_speed.w, pc.extent_time[a]);
    v2 += v * v;
  }
  p.w = sqrt(v2);
  positions[i] = p;
}

void main() {
  run();
  report_loop_ticks();
}
