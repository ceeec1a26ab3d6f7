#version 450
#extension GL_GOOGLE_include_directive : require
// raymarch_quads: the first pass of raymarch on a CPU device (compute/vk_volume.cpp). Texel id of
// the output holds the voxels (x, y), (x+1, y), (x, y+1), (x+1, y+1) of voxel id's slice, the
// neighbours clamped to the volume as trilinear clamps them, so that a raymarch sample fetches
// two texels where it gathered eight voxels (lavapipe's gathers cost most of a sample).
#include "kernel_base.glsl"
#include "engine/kernels/atom_params.h"

layout(binding = 1) uniform samplerBuffer volume_texels;  // r32f
layout(std430, binding = 2) writeonly buffer Quads { vec4 quads[]; };
MASAV_PUSH(RaymarchLayout);
float volume_at(uint index) { return texelFetch(volume_texels, int(index)).r; }

void main() {
  MASAV_LOAD_PUSH();
  const uint id = flat_invocation_id();
  const uvec3 d = p.dims;
  if (id >= d.x * d.y * d.z) return;
  const uint x = id % d.x, y = id / d.x % d.y;
  const uint x1 = x + 1u < d.x ? 1u : 0u, y1 = y + 1u < d.y ? d.x : 0u;
  quads[id] = vec4(volume_at(id), volume_at(id + x1), volume_at(id + y1), volume_at(id + y1 + x1));
}
