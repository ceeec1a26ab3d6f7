#version 450
#extension GL_GOOGLE_include_directive : require
// density[c] = (cell_end[c] - cell_start[c]) / (particles * cell^3). Twin of
// KernelBody<cloud_density> (engine/kernels/atom_body.h).
#include "kernel_base.glsl"
#include "engine/kernels/atom_params.h"

layout(std430, binding = 1) readonly buffer Start { uint cell_start[]; };
layout(std430, binding = 2) readonly buffer End { uint cell_end[]; };
layout(std430, binding = 3) writeonly buffer Density { float density[]; };
MASAV_PUSH(CloudDensityParams);

void main() {
  MASAV_LOAD_PUSH();
  const uint c = flat_invocation_id();
  const uvec3 d = p.grid.dims;
  const float cell = p.grid.cell_size;
  const float scale = 1.0 / (float(p.particles) * cell * cell * cell);
  if (c < d.x * d.y * d.z) density[c] = float(cell_end[c] - cell_start[c]) * scale;
  report_loop_ticks();
}
