#version 450
#extension GL_GOOGLE_include_directive : require
// voxelize, pass 2: p = count / particles, g = light sum / count, sample = s g + t count / max,
// written x fastest (volume-file order) from the grid's z-fastest cell ids.
#include "kernel_base.glsl"
#include "engine/kernels/atom_params.h"

layout(std430, binding = 1) readonly buffer Tallies { uint tallies[]; };
layout(std430, binding = 2) writeonly buffer P { float probability[]; };
layout(std430, binding = 3) writeonly buffer G { float mean_light[]; };
layout(std430, binding = 4) writeonly buffer S { float sample_out[]; };
MASAV_PUSH(VoxelizeParams);

void main() {
  MASAV_LOAD_PUSH();
  const uint o = flat_invocation_id();
  const uvec3 d = p.grid.dims;
  const uint cells = d.x * d.y * d.z;
  if (o < cells) {
    const uint x = o % d.x, y = (o / d.x) % d.y, z = o / (d.x * d.y);
    const uint c = (x * d.y + y) * d.z + z;
    const uint n = tallies[3u * c];
    const float sum = (float(tallies[3u * c + 2u]) * 4294967296.0 + float(tallies[3u * c + 1u])) *
                      (1.0 / 16777216.0);
    const float g = n > 0u ? sum / float(n) : 0.0;
    probability[o] = float(n) / float(p.grid.n);
    mean_light[o] = g;
    sample_out[o] = p.s * g + p.t * float(n) / float(tallies[3u * cells]);
  }
  report_loop_ticks();
}
