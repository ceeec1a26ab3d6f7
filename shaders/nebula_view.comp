#version 450
#extension GL_GOOGLE_include_directive : require
// nebula_view (thesis Eq. 2.5-2.6): light[i] = illumination[i] * P(tau_sct of i's cell,
// cos(light, view)) * exp(-tau_opt(x_i -> viewer)). Twin of nebula::view_light.
#include "kernel_base.glsl"
#include "grid_cell.glsl"
#include "slab.glsl"
#include "engine/kernels/atom_params.h"

// What the kernel only reads are uniform texel buffers (compute/vk_kernels.cpp): lavapipe fetches
// a texel with a gather, where it loads a storage buffer's element in a loop over the lanes.
layout(binding = 1) uniform samplerBuffer position_texels;      // rgba32f
layout(binding = 2) uniform samplerBuffer density_texels;       // r32f
layout(binding = 3) uniform samplerBuffer table_texels;         // r32f
layout(binding = 4) uniform samplerBuffer illumination_texels;  // r32f
float density_at(uint cell) { return texelFetch(density_texels, int(cell)).r; }
float table_at(uint index) { return texelFetch(table_texels, int(index)).r; }
layout(std430, binding = 5) writeonly buffer Out { float light[]; };
MASAV_PUSH(NebulaLightParams);

#define NEBULA_TABLE
#include "nebula.glsl"

void run() {
  const uint i = flat_invocation_id();
  if (i >= p.grid.n) return;
  const NebulaGrid g = NebulaGrid(p.grid.origin, p.grid.cell_size, p.grid.dims);
  const vec3 c = p.nucleus, v = p.viewer, x = texelFetch(position_texels, int(i)).xyz;
  const float kappa = p.kappa_a2, albedo = p.albedo;
  const uvec3 cc = grid_point_cell(x, p.grid.origin, p.grid.inv_cell, p.grid.dims);
  const float tau_sct = kappa * density_at(grid_cell_id(cc, p.grid.dims)) * g.cell;
  const vec3 to_x = x - c, to_v = v - x;
  const float lx = length(to_x), lv = length(to_v);
  const float mu = lx > 0.0 && lv > 0.0 ? dot(to_x, to_v) / (lx * lv) : 1.0;
  const float tau_view =
      path_integral(g, x, v, p.path, p.step_a0) * kappa / albedo;
  const float phase = nebula_phase(p.table_rows, p.table_bins,
                               p.table_tau_step, tau_sct, mu);
  light[i] = texelFetch(illumination_texels, int(i)).r * phase * exp(-tau_view);
}

void main() {
  MASAV_LOAD_PUSH();
  run();
  report_loop_ticks();
}
