#version 450
#extension GL_GOOGLE_include_directive : require
// voxelize, pass 1: per particle, its cell (the hash grid's fp32 rule) gains one count and the
// particle's light as a 2^-24 fixed-point integer in a 64-bit (lo, hi) sum; the largest count
// is kept with atomicMax. Integer sums: the same result whatever the order of the atomics.
#include "kernel_base.glsl"
#include "engine/kernels/atom_params.h"
#include "grid_cell.glsl"

layout(std430, binding = 1) readonly buffer Positions { vec4 positions[]; };
layout(std430, binding = 2) readonly buffer Light { float light[]; };
layout(std430, binding = 3) buffer Tallies { uint tallies[]; };  // count, lo, hi per cell; max
MASAV_PUSH(VoxelizeParams);

void run() {
  const uint i = flat_invocation_id();
  if (i >= p.grid.n) return;
  const uvec3 c = grid_point_cell(positions[i].xyz, p.grid.origin, p.grid.inv_cell, p.grid.dims);
  const uint id = grid_cell_id(c, p.grid.dims);
  const float v = min(1.0, max(0.0, light[i] * p.light_to_unit));
  const uint fw = uint(v * 16777216.0 + 0.5);
  const uint n = atomicAdd(tallies[3u * id], 1u) + 1u;
  const uint old = atomicAdd(tallies[3u * id + 1u], fw);
  if (old + fw < old) atomicAdd(tallies[3u * id + 2u], 1u);
  const uvec3 d = p.grid.dims;
  atomicMax(tallies[3u * (d.x * d.y * d.z)], n);
}

void main() {
  MASAV_LOAD_PUSH();
  run();
  report_loop_ticks();
}
