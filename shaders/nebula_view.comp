#version 450
#extension GL_GOOGLE_include_directive : require
// nebula_view (thesis Eq. 2.5-2.6): light[i] = illumination[i] * P(tau_sct of i's cell,
// cos(light, view)) * exp(-tau_opt(x_i -> viewer)). Twin of nebula::view_light.
#include "kernel_base.glsl"
#include "grid_cell.glsl"
#include "slab.glsl"

layout(std430, binding = 1) readonly buffer Positions { vec4 positions[]; };
layout(std430, binding = 2) readonly buffer Density { float density[]; };
layout(std430, binding = 3) readonly buffer Table { float table_data[]; };
layout(std430, binding = 4) readonly buffer Illum { float illumination[]; };
layout(std430, binding = 5) writeonly buffer Out { float light[]; };
layout(push_constant) uniform Push {
  vec4 origin_inv_cell;
  uvec4 dims_n;
  vec4 nucleus_cell;
  vec4 viewer_kappa;
  vec4 power_albedo_core_step;
  uvec4 path_rows_bins;
} pc;

#define NEBULA_TABLE
#include "nebula.glsl"

void run() {
  const uint i = flat_invocation_id();
  if (i >= pc.dims_n.w) return;
  const NebulaGrid g = NebulaGrid(pc.origin_inv_cell.xyz, pc.nucleus_cell.w, pc.dims_n.xyz);
  const vec3 c = pc.nucleus_cell.xyz, v = pc.viewer_kappa.xyz, x = positions[i].xyz;
  const float kappa = pc.viewer_kappa.w, albedo = pc.power_albedo_core_step.y;
  const uvec3 cc = grid_point_cell(x, pc.origin_inv_cell.xyz, pc.origin_inv_cell.w, pc.dims_n.xyz);
  const float tau_sct = kappa * density[grid_cell_id(cc, pc.dims_n.xyz)] * g.cell;
  const vec3 to_x = x - c, to_v = v - x;
  const float lx = length(to_x), lv = length(to_v);
  const float mu = lx > 0.0 && lv > 0.0 ? dot(to_x, to_v) / (lx * lv) : 1.0;
  const float tau_view =
      path_integral(g, x, v, pc.path_rows_bins.x, pc.power_albedo_core_step.w) * kappa / albedo;
  const float p = nebula_phase(pc.path_rows_bins.y, pc.path_rows_bins.z,
                               uintBitsToFloat(pc.path_rows_bins.w), tau_sct, mu);
  light[i] = illumination[i] * p * exp(-tau_view);
}

void main() {
  run();
  report_loop_ticks();
}
