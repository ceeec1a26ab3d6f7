#version 450
#extension GL_GOOGLE_include_directive : require
// Fluid surface, passes 2 to 5: the nearest-depth plane smoothed by a bilateral filter along
// rows (into the kAcross plane), then columns (into kSmoothed), twice (a separable
// approximation), about a sphere radius or two wide: neighbours across a depth step of more than
// a few radii do not blend, so the spheres' bumps merge into one surface and separate sheets stay
// apart. Writes a plane, no colour.
#include "fluid_common.glsl"

layout(std430, set = 0, binding = 0) buffer Fluid { uint fluid[]; };
layout(push_constant) uniform Push {
  uvec4 shape;  // width, height, the plane read, the plane written
  vec4 sphere;  // x: sphere radius (world), y: pixels per world unit at view depth 1,
                // z: the filter's width, w: its depth range, both in sphere radii
} pc;

layout(location = 0) out vec4 out_color;

// The filter's reach: at most this many taps on each side (wider filters take strides).
const int kTaps = 24;

float read_depth(ivec2 p) {
  if (any(lessThan(p, ivec2(0))) || any(greaterThanEqual(p, ivec2(pc.shape.xy)))) return kEmpty;
  return uintBitsToFloat(
      fluid[pc.shape.z * pc.shape.x * pc.shape.y + uint(p.y) * pc.shape.x + uint(p.x)]);
}

void main() {
  const ivec2 p = ivec2(gl_FragCoord.xy);
  const uint i = pc.shape.w * pc.shape.x * pc.shape.y + uint(p.y) * pc.shape.x + uint(p.x);
  const float z = read_depth(p);
  out_color = vec4(0.0);
  if (z >= kEmpty) {
    fluid[i] = floatBitsToUint(kEmpty);
    return;
  }
  // The filter's standard deviation: pc.sphere.z sphere radii, in pixels at this depth.
  const float sigma_px = max(pc.sphere.z * pc.sphere.x * pc.sphere.y / max(z, 1e-6), 1.0);
  const int stride = max(1, int(ceil(2.0 * sigma_px / float(kTaps))));
  const float sigma_z = pc.sphere.w * pc.sphere.x;
  const ivec2 dir = pc.shape.w == kAcross ? ivec2(1, 0) : ivec2(0, 1);
  float sum = 0.0, weights = 0.0;
  for (int k = -kTaps; k <= kTaps; ++k) {
    const float off = float(k * stride);
    if (abs(off) > 2.0 * sigma_px + 0.5) continue;
    const float zk = read_depth(p + dir * (k * stride));
    if (zk >= kEmpty) continue;
    const float dz = (zk - z) / sigma_z;
    const float w = exp(-0.5 * off * off / (sigma_px * sigma_px) - 0.5 * dz * dz);
    sum += w * zk;
    weights += w;
  }
  fluid[i] = floatBitsToUint(sum / weights);
}
