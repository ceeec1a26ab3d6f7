#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_arithmetic : require
// One DFSPH iteration's second half (or a solve's warm start, p.first = 1): each moving sorted
// particle's velocity corrected by the pressure its kappa and its neighbours' (and their wall
// images') give, v -= dt w sum_j (k_i + k_j) m grad W_ij. Reports the largest speed and
// non-finite velocities. Twin of sph::dfsph_correction_of (engine/kernels/dfsph_kernels.h).
#include "kernel_base.glsl"

// What the kernel only reads are uniform texel buffers (compute/vk_kernels.cpp): lavapipe fetches
// a texel with a gather, where it loads a storage buffer's element in a loop over the lanes.
layout(binding = 1) uniform samplerBuffer positions_texels;  // rgba32f
vec4 position_at(uint i) { return texelFetch(positions_texels, int(i)); }
layout(binding = 2) uniform samplerBuffer kappa_texels;  // r32f
float kappa_at(uint i) { return texelFetch(kappa_texels, int(i)).r; }
layout(binding = 3) uniform usamplerBuffer cells_texels;  // r32ui
uint cell_at(uint i) { return texelFetch(cells_texels, int(i)).r; }
layout(binding = 4) uniform usamplerBuffer cell_start_texels;  // r32ui
uint cell_start_at(uint i) { return texelFetch(cell_start_texels, int(i)).r; }
layout(binding = 5) uniform usamplerBuffer cell_end_texels;  // r32ui
uint cell_end_at(uint i) { return texelFetch(cell_end_texels, int(i)).r; }
layout(std430, binding = 6) buffer Velocities { vec4 velocities[]; };
layout(std430, binding = 7) buffer Stats { uint stats[]; };
layout(binding = 8) uniform usamplerBuffer residual_texels;  // r32ui; read if p.stop_slot is set
uint residual_at(uint i) { return texelFetch(residual_texels, int(i)).r; }
layout(binding = 9) uniform usamplerBuffer neighbor_rows_texels;  // r32ui
uint neighbor_row_at(uint i) { return texelFetch(neighbor_rows_texels, int(i)).r; }

#include "sph.glsl"
#include "sph_walk.glsl"
#include "engine/kernels/dfsph_params.h"

MASAV_PUSH(DfsphLayout);

#include "dfsph.glsl"

uint g_self;
vec3 g_xi;
float g_ki;
SphMirrors g_m;
vec3 g_acc = vec3(0.0);

void add_image(vec3 xj, float k, uint s) {
  vec3 d;
  float r2;
  if (dfsph_image(g_xi, xj, g_m, s, p.h2, d, r2)) g_acc += k * dfsph_gradient(d, r2, p);
}
void dfsph_visit(uint j, bool images) {
  const vec3 xj = position_at(j).xyz;
  const vec3 d = g_xi - xj;
  const float r2 = dot(d, d);
  if (!(r2 < p.h2)) return;
  const float k = g_ki + (j == g_self ? g_ki : kappa_at(j));
  if (j != g_self) g_acc += k * dfsph_gradient(d, r2, p);
  if (images && g_m.axes != 0u) {
    add_image(xj, k, 1u);
    add_image(xj, k, 2u);
    add_image(xj, k, 3u);
    add_image(xj, k, 4u);
    add_image(xj, k, 5u);
    add_image(xj, k, 6u);
    add_image(xj, k, 7u);
  }
}

void main() {
  MASAV_LOAD_PUSH();
  // The iteration before converged: this one, queued behind it, does nothing.
  if (p.stop_slot != kDfsphNoStop &&
      dfsph_stopped_at(uvec2(residual_at(2u * p.stop_slot), residual_at(2u * p.stop_slot + 1u)), p))
    return;
  // The range computed, [begin, end) of the n; the others are only read as neighbours.
  const uint i = p.begin + flat_invocation_id();
  vec4 pw = vec4(0.0);
  if (i < p.end) pw = position_at(i);
  // Pinned particles never move: their lanes walk nothing.
  const bool live = i < p.end && pw.w > 0.0;
  g_self = i;
  g_xi = pw.xyz;
  g_ki = live ? kappa_at(i) : 0.0;
  ivec3 cc = ivec3(-4);
  if (live) cc = sph_cell_coords(cell_at(i), p.dims);
  g_m = dfsph_mirrors(g_xi, p);
  uint candidates = 0u;
  bool overflow = false, bad = false;
  dfsph_walk(live, i, cc, sph_walls_near(g_m.axes), candidates, overflow);
  float speed2 = 0.0;
  if (live) {
    const vec3 dv = (p.first != 0u ? -p.dt * p.warm_scale : -p.dt) * g_acc;
    const vec4 v0 = velocities[i];
    const vec3 v = v0.xyz + pw.w * dv;
    velocities[i] = vec4(v, v0.w);
    bad = !sph_finite(v);
    if (!bad) speed2 = dot(v, v);
  }
  const uint max_s2 = subgroupMax(floatBitsToUint(speed2));
  const uint nonfinite = subgroupMax(bad ? ~i : 0u);
  if (subgroupElect()) {
    atomicMax(stats[kSphStatMaxSpeed2], max_s2);
    if (nonfinite != 0u) atomicMax(stats[kSphStatNonFinite], nonfinite);
  }
  report_loop_ticks();
}
