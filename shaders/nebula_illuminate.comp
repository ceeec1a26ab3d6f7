#version 450
#extension GL_GOOGLE_include_directive : require
// nebula_illuminate (thesis Eq. 2.4): illumination[i] = Phi / (4 pi r^2) exp(-tau_opt), the
// optical depth integrated through the density grid from the nucleus to particle i. Twin of
// nebula::illumination (engine/kernels/nebula_math.h).
#include "kernel_base.glsl"
#include "grid_cell.glsl"
#include "slab.glsl"

layout(std430, binding = 1) readonly buffer Positions { vec4 positions[]; };
layout(std430, binding = 2) readonly buffer Density { float density[]; };
layout(std430, binding = 3) writeonly buffer Out { float illumination[]; };
layout(push_constant) uniform Push {
  vec4 origin_inv_cell;
  uvec4 dims_n;
  vec4 nucleus_cell;  // nucleus.xyz, cell size
  vec4 viewer_kappa;
  vec4 power_albedo_core_step;
  uvec4 path_rows_bins;  // path, table rows, table bins, table tau step (float bits)
} pc;

#include "nebula.glsl"

void run() {
  const uint i = flat_invocation_id();
  if (i >= pc.dims_n.w) return;
  const NebulaGrid g = NebulaGrid(pc.origin_inv_cell.xyz, pc.nucleus_cell.w, pc.dims_n.xyz);
  const vec3 c = pc.nucleus_cell.xyz, x = positions[i].xyz;
  const float r = max(length(x - c), pc.power_albedo_core_step.z);
  const float tau = path_integral(g, c, x, pc.path_rows_bins.x, pc.power_albedo_core_step.w) *
                    pc.viewer_kappa.w / pc.power_albedo_core_step.y;
  illumination[i] = pc.power_albedo_core_step.x / (4.0 * NEBULA_PI * r * r) * exp(-tau);
}

void main() {
  run();
  report_loop_ticks();
}
