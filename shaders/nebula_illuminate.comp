#version 450
#extension GL_GOOGLE_include_directive : require
// nebula_illuminate (thesis Eq. 2.4): illumination[i] = Phi / (4 pi r^2) exp(-tau_opt), the
// optical depth integrated through the density grid from the nucleus to particle i. Twin of
// nebula::illumination (engine/kernels/nebula_math.h).
#include "kernel_base.glsl"
#include "grid_cell.glsl"
#include "slab.glsl"
#include "engine/kernels/atom_params.h"

// What the kernel only reads are uniform texel buffers (compute/vk_kernels.cpp): lavapipe fetches
// a texel with a gather, where it loads a storage buffer's element in a loop over the lanes.
layout(binding = 1) uniform samplerBuffer position_texels;  // rgba32f
layout(binding = 2) uniform samplerBuffer density_texels;   // r32f
float density_at(uint cell) { return texelFetch(density_texels, int(cell)).r; }
layout(std430, binding = 3) writeonly buffer Out { float illumination[]; };
MASAV_PUSH(NebulaLightParams);

#include "nebula.glsl"

void run() {
  const uint i = flat_invocation_id();
  if (i >= p.grid.n) return;
  const NebulaGrid g = NebulaGrid(p.grid.origin, p.grid.cell_size, p.grid.dims);
  const vec3 c = p.nucleus, x = texelFetch(position_texels, int(i)).xyz;
  const float r = max(length(x - c), p.core_radius_a0);
  const float tau = path_integral(g, c, x, p.path, p.step_a0) *
                    p.kappa_a2 / p.albedo;
  illumination[i] = p.source_power_lm / (4.0 * NEBULA_PI * r * r) * exp(-tau);
}

void main() {
  MASAV_LOAD_PUSH();
  run();
  report_loop_ticks();
}
