#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_arithmetic : require
// One DFSPH iteration's first half: each sorted particle's density change rate over its
// neighbours within h and the wall images (mirrored velocities), its kappa (p.solve: density or
// divergence), the solve's running kappa sum, and the residual summed as integers into the
// iteration's slot (one 64-bit add per subgroup). Twin of sph::dfsph_rate_of
// (engine/kernels/dfsph_kernels.h).
#include "kernel_base.glsl"

// What the kernel only reads are uniform texel buffers (compute/vk_kernels.cpp): lavapipe fetches
// a texel with a gather, where it loads a storage buffer's element in a loop over the lanes.
layout(binding = 1) uniform samplerBuffer positions_texels;  // rgba32f
vec4 position_at(uint i) { return texelFetch(positions_texels, int(i)); }
layout(binding = 2) uniform samplerBuffer velocities_texels;  // rgba32f
vec4 velocity_at(uint i) { return texelFetch(velocities_texels, int(i)); }
layout(binding = 3) uniform samplerBuffer density_texels;  // r32f
float density_at(uint i) { return texelFetch(density_texels, int(i)).r; }
layout(binding = 4) uniform samplerBuffer factor_texels;  // r32f
float factor_at(uint i) { return texelFetch(factor_texels, int(i)).r; }
layout(binding = 5) uniform usamplerBuffer cells_texels;  // r32ui
uint cell_at(uint i) { return texelFetch(cells_texels, int(i)).r; }
layout(binding = 6) uniform usamplerBuffer cell_start_texels;  // r32ui
uint cell_start_at(uint i) { return texelFetch(cell_start_texels, int(i)).r; }
layout(binding = 7) uniform usamplerBuffer cell_end_texels;  // r32ui
uint cell_end_at(uint i) { return texelFetch(cell_end_texels, int(i)).r; }
layout(std430, binding = 8) writeonly buffer Kappa { float kappa[]; };
layout(std430, binding = 9) buffer KappaSum { float kappa_sum[]; };
layout(std430, binding = 10) buffer Residual { uint residual[]; };
layout(binding = 11) uniform usamplerBuffer neighbor_rows_texels;  // r32ui
uint neighbor_row_at(uint i) { return texelFetch(neighbor_rows_texels, int(i)).r; }

#include "sph.glsl"
#include "sph_walk.glsl"
#include "engine/kernels/dfsph_params.h"

MASAV_PUSH(DfsphLayout);

#include "dfsph.glsl"

uint g_self;
vec3 g_xi, g_vi;
SphMirrors g_m;
float g_div = 0.0;
uint g_neighbors = 0u;

void add_image(vec3 xj, vec3 vj, uint s) {
  vec3 d;
  float r2;
  if (dfsph_image(g_xi, xj, g_m, s, p.h2, d, r2))
    g_div += dot(dfsph_gradient(d, r2, p), g_vi - dfsph_mirror_velocity(vj, s));
}
void dfsph_visit(uint j, bool images) {
  const vec3 xj = position_at(j).xyz;
  const vec3 d = g_xi - xj;
  const float r2 = dot(d, d);
  if (!(r2 < p.h2)) return;
  ++g_neighbors;
  const vec3 vj = j == g_self ? g_vi : velocity_at(j).xyz;
  if (j != g_self) g_div += dot(dfsph_gradient(d, r2, p), g_vi - vj);
  if (images && g_m.axes != 0u) {
    add_image(xj, vj, 1u);
    add_image(xj, vj, 2u);
    add_image(xj, vj, 3u);
    add_image(xj, vj, 4u);
    add_image(xj, vj, 5u);
    add_image(xj, vj, 6u);
    add_image(xj, vj, 7u);
  }
}

void main() {
  MASAV_LOAD_PUSH();
  // The iteration before converged: this one, queued behind it, does nothing.
  if (p.stop_slot != kDfsphNoStop &&
      dfsph_stopped_at(uvec2(residual[2u * p.stop_slot], residual[2u * p.stop_slot + 1u]), p))
    return;
  // The range computed, [begin, end) of the n (a rank's own particles); the others are only
  // read as neighbours.
  const uint i = p.begin + flat_invocation_id();
  const bool live = i < p.end;
  g_self = i;
  g_xi = vec3(0.0);
  g_vi = vec3(0.0);
  ivec3 cc = ivec3(-4);
  float w = 0.0;
  if (live) {
    const vec4 pw = position_at(i);
    g_xi = pw.xyz;
    w = pw.w;
    g_vi = velocity_at(i).xyz;
    cc = sph_cell_coords(cell_at(i), p.dims);
  }
  g_m = dfsph_mirrors(g_xi, p);
  uint candidates = 0u;
  bool overflow = false;
  dfsph_walk(live, i, cc, sph_walls_near(g_m.axes), candidates, overflow);
  uint units = 0u;
  if (live) {
    float k, res;
    if (p.solve == DfsphSolve_density) {
      const float excess = max(density_at(i) + p.dt * g_div - p.rest_density, 0.0);
      k = excess * factor_at(i) / (p.dt * p.dt);
      res = excess * p.inv_rest_density;
    } else {
      const float rate = max(g_neighbors >= p.min_neighbors ? g_div : 0.0, 0.0);
      k = rate * factor_at(i) / p.dt;
      res = p.dt * rate * p.inv_rest_density;
    }
    kappa[i] = k;
    kappa_sum[i] = (p.first != 0u ? p.warm_scale * kappa_sum[i] : kappa_sum[i]) + k;
    if (w > 0.0) units = dfsph_residual_units(res);
  }
  const uint sum = subgroupAdd(units);  // at most 128 x 2^24: fits
  if (subgroupElect() && sum != 0u) {
    const uint old = atomicAdd(residual[2u * p.slot], sum);
    if (old > 0xffffffffu - sum) atomicAdd(residual[2u * p.slot + 1u], 1u);  // low word wrapped
  }
  report_loop_ticks();
}
