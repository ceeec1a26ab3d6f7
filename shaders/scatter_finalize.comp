#version 450
#extension GL_GOOGLE_include_directive : require
// table[i] = 64-bit tally i / (2^20 * photons_per_row): weight fractions of the row's photons.
#include "kernel_base.glsl"
#include "engine/kernels/atom_params.h"

layout(std430, binding = 1) readonly buffer Tallies { uint tallies[]; };
layout(std430, binding = 2) writeonly buffer Table { float table_out[]; };
MASAV_PUSH(ScatterFinalizeParams);

void main() {
  MASAV_LOAD_PUSH();
  const uint i = flat_invocation_id();
  if (i < p.entries)
    table_out[i] = (float(tallies[2u * i + 1u]) * 4294967296.0 + float(tallies[2u * i])) * p.scale;
  report_loop_ticks();
}
