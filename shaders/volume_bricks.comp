#version 450
#extension GL_GOOGLE_include_directive : require
// volume_bricks: per brick of BRICK^3 voxels plus the one-voxel apron that trilinear sampling
// reads, (min, max, largest transfer alpha over [min, max], 1: the stride a ray crosses it in,
// which volume_brick_skip widens): the GLSL twin of KernelBody<volume_bricks>
// (engine/kernels/atom_body.h). raymarch skips bricks with alpha 0. At most (16 + 1)^3 + 4096
// loop iterations per invocation.
#include "kernel_base.glsl"
#include "engine/kernels/atom_params.h"

layout(std430, binding = 1) readonly buffer Volume { float volume_data[]; };
layout(std430, binding = 2) readonly buffer Tf { vec4 tf[]; };
layout(std430, binding = 3) writeonly buffer Bricks { vec4 bricks[]; };
MASAV_PUSH(VolumeBrickParams);

vec2 value_range(uvec3 first, uvec3 last, uvec3 d) {
  float lo = 3.0e38, hi = -3.0e38;
  for (uint k = first.z; k <= last.z; ++k)
    for (uint j = first.y; j <= last.y; ++j)
      for (uint i = first.x; i <= last.x; ++i) {
        LOOP_TICK();
        const float v = volume_data[(k * d.y + j) * d.x + i];
        lo = min(lo, v);
        hi = max(hi, v);
      }
  return vec2(lo, hi);
}

// Largest alpha of the entries whose linear pieces cover the range after normalisation.
float range_alpha(vec2 range) {
  const uint size = p.tf_size;
  const float value_scale = 1.0 / (p.volume.value_max - p.volume.value_min);
  const float nlo = clamp((range.x - p.volume.value_min) * value_scale, 0.0, 1.0);
  const float nhi = clamp((range.y - p.volume.value_min) * value_scale, 0.0, 1.0);
  const uint k0 = uint(nlo * float(size - 1u));
  const uint k1 = min(uint(ceil(nhi * float(size - 1u))), size - 1u);
  float amax = 0.0;
  for (uint k = k0; k <= k1; ++k) {
    LOOP_TICK();
    amax = max(amax, tf[k].a);
  }
  return amax;
}

void run() {
  const uint id = flat_invocation_id();
  const uvec3 d = p.volume.dims;
  const uvec3 nb = (d + p.brick - 1u) / p.brick;
  if (id >= nb.x * nb.y * nb.z) return;
  const uvec3 b = uvec3(id % nb.x, (id / nb.x) % nb.y, id / (nb.x * nb.y));
  const vec2 range = value_range(b * p.brick, min((b + 1u) * p.brick, d - 1u), d);
  bricks[id] = vec4(range, range_alpha(range), 1.0);
}

void main() {
  MASAV_LOAD_PUSH();
  run();
  report_loop_ticks();
}
