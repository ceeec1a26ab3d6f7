#version 450
#extension GL_GOOGLE_include_directive : require
// volume_brick_skip: one pass of the max-norm distance transform over the brick grid, both ways
// at once (to the nearest occupied brick: low 16 bits; to the nearest empty one: high 16); pass 2
// writes the distance to the other kind to bricks[].w. The GLSL twin of
// KernelBody<volume_brick_skip> (engine/kernels/atom_body.h). At most 2 radius + 1 <= 511 loop
// iterations per invocation.
#include "kernel_base.glsl"
#include "engine/kernels/atom_params.h"

layout(std430, binding = 1) buffer Bricks { vec4 bricks[]; };
layout(std430, binding = 2) buffer Distances { uint distances[]; };
MASAV_PUSH(BrickSkipParams);

void run() {
  const uint id = flat_invocation_id();
  const uvec3 n = p.bricks;
  const uint count = n.x * n.y * n.z;
  if (id >= count) return;
  const uint a = p.axis;
  const uint at = a == 0u ? id % n.x : (a == 1u ? id / n.x % n.y : id / (n.x * n.y));
  const uint stride = a == 0u ? 1u : (a == 1u ? n.x : n.x * n.y);
  const uint line = id - at * stride;  // the line's first brick
  const uint far = p.radius + 1u;
  const uint first = at > p.radius ? at - p.radius : 0u;
  const uint last = min(at + p.radius, n[a] - 1u);
  uint to_occupied = far, to_empty = far;
  for (uint c = first; c <= last; ++c) {
    LOOP_TICK();
    const uint j = line + c * stride;
    const uint off = c > at ? c - at : at - c;
    uint occupied, empty;
    if (a == 0u) {
      const bool o = bricks[j].z > 0.0;
      occupied = o ? 0u : far;
      empty = o ? far : 0u;
    } else {
      const uint w = distances[(a - 1u) * count + j];
      occupied = w & 0xffffu;
      empty = w >> 16;
    }
    to_occupied = min(to_occupied, max(off, occupied));
    to_empty = min(to_empty, max(off, empty));
  }
  if (a < 2u)
    distances[a * count + id] = to_occupied | (to_empty << 16);
  else
    bricks[id].w = float(bricks[id].z > 0.0 ? to_empty : to_occupied);
}

void main() {
  MASAV_LOAD_PUSH();
  run();
  report_loop_ticks();
}
