#version 450
#extension GL_GOOGLE_include_directive : require
// volume_bricks: per brick of BRICK^3 voxels plus the one-voxel apron that trilinear sampling
// reads, (min, max, largest transfer alpha over [min, max], 0). A brick with alpha 0 is skipped
// by raymarch. At most (32 + 1)^3 + 4096 loop iterations per invocation.
#include "kernel_base.glsl"

layout(std430, binding = 1) readonly buffer Volume { float volume_data[]; };
layout(std430, binding = 2) readonly buffer Tf { vec4 tf[]; };
layout(std430, binding = 3) writeonly buffer Bricks { vec4 bricks[]; };
layout(push_constant) uniform Push {
  uvec4 dims_tf;  // dims.xyz, tf size
  uint brick;
  float value_min;
  float value_scale;
} pc;

void run() {
  const uint id = flat_invocation_id();
  const uvec3 d = pc.dims_tf.xyz;
  const uvec3 nb = (d + pc.brick - 1u) / pc.brick;
  if (id >= nb.x * nb.y * nb.z) return;
  const uvec3 b = uvec3(id % nb.x, (id / nb.x) % nb.y, id / (nb.x * nb.y));
  const uvec3 first = b * pc.brick, last = min((b + 1u) * pc.brick, d - 1u);
  float lo = 3.0e38, hi = -3.0e38;
  for (uint k = first.z; k <= last.z; ++k)
    for (uint j = first.y; j <= last.y; ++j)
      for (uint i = first.x; i <= last.x; ++i) {
        LOOP_TICK();
        const float v = volume_data[(k * d.y + j) * d.x + i];
        lo = min(lo, v);
        hi = max(hi, v);
      }
  const uint size = pc.dims_tf.w;
  const float nlo = clamp((lo - pc.value_min) * pc.value_scale, 0.0, 1.0);
  const float nhi = clamp((hi - pc.value_min) * pc.value_scale, 0.0, 1.0);
  const uint k0 = uint(nlo * float(size - 1u));
  const uint k1 = min(uint(ceil(nhi * float(size - 1u))), size - 1u);
  float amax = 0.0;
  for (uint k = k0; k <= k1; ++k) {
    LOOP_TICK();
    amax = max(amax, tf[k].a);
  }
  bricks[id] = vec4(lo, hi, amax, 0.0);
}

void main() {
  run();
  report_loop_ticks();
}
