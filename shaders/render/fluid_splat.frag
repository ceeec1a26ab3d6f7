#version 450
#extension GL_GOOGLE_include_directive : require
// Fluid surface, pass 1: every sprite pixel of every particle adds its sphere's chord (thickness)
// and colour, and keeps the nearest sphere point's view depth. Writes no colour.
#include "fluid_common.glsl"

layout(std430, set = 0, binding = 3) buffer Fluid { uint fluid[]; };
layout(push_constant) uniform Push {
  mat4 view_proj;
  vec4 size;
  vec4 range;
  uvec4 mode;  // w: frame width (range.w: its height)
  vec4 eye;
} pc;

layout(location = 0) in vec3 v_color;
layout(location = 1) flat in vec4 v_depth;
layout(location = 0) out vec4 out_color;

void main() {
  const vec2 d = gl_PointCoord * 2.0 - 1.0;
  const float r2 = dot(d, d);
  if (r2 > 1.0) discard;
  const float k = sqrt(1.0 - r2);
  const uint plane = pc.mode.w * uint(pc.range.w);  // width x height
  const uint i = uint(gl_FragCoord.y) * pc.mode.w + uint(gl_FragCoord.x);
  // Clip w is the view depth; it is linear along the line to the sphere's nearest point.
  const float depth = mix(v_depth.y, v_depth.w, k);
  atomicMin(fluid[kNearest * plane + i], floatBitsToUint(max(depth, 0.0)));
  atomicAdd(fluid[kThickness * plane + i], uint(512.0 * k + 0.5));
  const vec3 c = clamp(v_color, 0.0, 1.0) * (255.0 * k);
  atomicAdd(fluid[kRed * plane + i], uint(c.r + 0.5));
  atomicAdd(fluid[kGreen * plane + i], uint(c.g + 0.5));
  atomicAdd(fluid[kBlue * plane + i], uint(c.b + 0.5));
  atomicAdd(fluid[kWeight * plane + i], uint(255.0 * k + 0.5));
  out_color = vec4(0.0);
}
