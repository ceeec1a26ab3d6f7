#version 450
#extension GL_GOOGLE_include_directive : require
// Fluid surface, passes 2 and 3: the nearest-depth plane smoothed by a 2D bilateral filter about
// a sphere radius or two wide, twice (kNearest into kAcross, then into kSmoothed). Round, not
// separable: a rows-then-columns filter leaves the last direction's streaks wherever a drop sits
// in front of the body. Neighbours more than a few radii nearer or farther take no part (a
// narrow depth range), so the spheres' bumps merge into one surface while drops in front and
// sheets behind stay apart. Writes a plane, no colour.
#include "fluid_common.glsl"

layout(std430, set = 0, binding = 0) buffer Fluid { uint fluid[]; };
layout(push_constant) uniform Push {
  uvec4 shape;  // width, height, the plane read, the plane written
  vec4 sphere;  // x: sphere radius (world), y: pixels per world unit at view depth 1,
                // z: the filter's width, w: its depth range, both in sphere radii
} pc;

layout(location = 0) out vec4 out_color;

// The filter's reach: this many pixels on each side per axis. Every pixel within it is read
// (a strided filter aliases into dotted patterns on the spheres); a filter wanted wider is
// capped at a standard deviation of kTaps / 2 pixels.
const int kTaps = 8;
// Beyond this many depth ranges a neighbour is another sheet, not this one's bump.
const float kDepthCut = 1.0;

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
  const float sigma_px =
      clamp(pc.sphere.z * pc.sphere.x * pc.sphere.y / max(z, 1e-6), 1.0, 0.5 * float(kTaps));
  const int reach = min(kTaps, int(2.0 * sigma_px + 0.5));
  const float sigma_z = pc.sphere.w * pc.sphere.x;
  float sum = 0.0, weights = 0.0;
  const float reach2 = (2.0 * sigma_px + 0.5) * (2.0 * sigma_px + 0.5);
  for (int ky = -reach; ky <= reach; ++ky) {
    for (int kx = -reach; kx <= reach; ++kx) {
      const vec2 off = vec2(kx, ky);
      const float d2 = dot(off, off);
      if (d2 > reach2) continue;
      const float zk = read_depth(p + ivec2(kx, ky));
      if (zk >= kEmpty) continue;
      const float dz = (zk - z) / sigma_z;
      if (abs(dz) > kDepthCut) continue;
      const float w = exp(-0.5 * d2 / (sigma_px * sigma_px) - 0.5 * dz * dz);
      sum += w * zk;
      weights += w;
    }
  }
  fluid[i] = floatBitsToUint(sum / weights);
}
