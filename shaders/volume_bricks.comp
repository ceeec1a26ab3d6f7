#version 450
#extension GL_GOOGLE_include_directive : require
// volume_bricks: per brick of BRICK^3 voxels plus the one-voxel apron that trilinear sampling
// reads, (min, max, largest transfer alpha over [min, max], 0). A brick with alpha 0 is skipped
// by raymarch. At most (32 + 1)^3 + 4096 loop iterations per invocation.
#include "kernel_base.glsl"
#include "engine/kernels/atom_params.h"

layout(std430, binding = 1) readonly buffer Volume { float volume_data[]; };
layout(std430, binding = 2) readonly buffer Tf { vec4 tf[]; };
layout(std430, binding = 3) writeonly buffer Bricks { vec4 bricks[]; };
MASAV_PUSH(VolumeBrickParams);

void run() {
  const uint id = flat_invocation_id();
  const uvec3 d = p.volume.dims;
  const uvec3 nb = (d + p.brick - 1u) / p.brick;
  if (id >= nb.x * nb.y * nb.z) return;
  const uvec3 b = uvec3(id % nb.x, (id / nb.x) % nb.y, id / (nb.x * nb.y));
  const uvec3 first = b * p.brick, last = min((b + 1u) * p.brick, d - 1u);
  float lo = 3.0e38, hi = -3.0e38;
  for (uint k = first.z; k <= last.z; ++k)
    for (uint j = first.y; j <= last.y; ++j)
      for (uint i = first.x; i <= last.x; ++i) {
        LOOP_TICK();
        const float v = volume_data[(k * d.y + j) * d.x + i];
        lo = min(lo, v);
        hi = max(hi, v);
      }
  const uint size = p.tf_size;
  const float value_scale = 1.0 / (p.volume.value_max - p.volume.value_min);
  const float nlo = clamp((lo - p.volume.value_min) * value_scale, 0.0, 1.0);
  const float nhi = clamp((hi - p.volume.value_min) * value_scale, 0.0, 1.0);
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
