#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_arithmetic : require
// The DFSPH factor f_i = 1 / (|sum_j m grad W_ij|^2 + sum_j |m grad W_ij|^2) of each sorted
// particle over its neighbours within h and the wall images (sph::WallMirrors). Twin of
// sph::dfsph_factor_of (engine/kernels/dfsph_kernels.h).
#include "kernel_base.glsl"

// What the kernel only reads are uniform texel buffers (compute/vk_kernels.cpp): lavapipe fetches
// a texel with a gather, where it loads a storage buffer's element in a loop over the lanes.
layout(binding = 1) uniform samplerBuffer positions_texels;  // rgba32f
vec4 position_at(uint i) { return texelFetch(positions_texels, int(i)); }
layout(binding = 2) uniform usamplerBuffer cells_texels;  // r32ui
uint cell_at(uint i) { return texelFetch(cells_texels, int(i)).r; }
layout(binding = 3) uniform usamplerBuffer cell_start_texels;  // r32ui
uint cell_start_at(uint i) { return texelFetch(cell_start_texels, int(i)).r; }
layout(binding = 4) uniform usamplerBuffer cell_end_texels;  // r32ui
uint cell_end_at(uint i) { return texelFetch(cell_end_texels, int(i)).r; }
layout(std430, binding = 5) writeonly buffer Factor { float factor[]; };
layout(std430, binding = 6) buffer Stats { uint stats[]; };
layout(binding = 7) uniform usamplerBuffer neighbor_rows_texels;  // r32ui
uint neighbor_row_at(uint i) { return texelFetch(neighbor_rows_texels, int(i)).r; }

#include "sph.glsl"
#include "sph_walk.glsl"
#include "engine/kernels/dfsph_params.h"

MASAV_PUSH(DfsphLayout);

#include "dfsph.glsl"

uint g_self;
vec3 g_xi;
SphMirrors g_m;
vec3 g_sum = vec3(0.0);
float g_sum2 = 0.0;

void add_gradient(vec3 d, float r2) {
  const vec3 g = dfsph_gradient(d, r2, p);
  g_sum += g;
  g_sum2 += dot(g, g);
}
// A neighbour's image counts like a neighbour, the particle's own twice in the gradient sum and
// not in the squares (sph::dfsph_factor_of).
void add_image(vec3 xj, bool own, uint s) {
  vec3 d;
  float r2;
  if (!dfsph_image(g_xi, xj, g_m, s, p.h2, d, r2)) return;
  if (own)
    g_sum += 2.0 * dfsph_gradient(d, r2, p);
  else
    add_gradient(d, r2);
}
void dfsph_visit(uint j, bool images) {
  const vec3 xj = position_at(j).xyz;
  const vec3 d = g_xi - xj;
  const float r2 = dot(d, d);
  if (!(r2 < p.h2)) return;
  if (j != g_self) add_gradient(d, r2);
  if (images && g_m.axes != 0u) {
    const bool own = j == g_self;
    add_image(xj, own, 1u);
    add_image(xj, own, 2u);
    add_image(xj, own, 3u);
    add_image(xj, own, 4u);
    add_image(xj, own, 5u);
    add_image(xj, own, 6u);
    add_image(xj, own, 7u);
  }
}

void main() {
  MASAV_LOAD_PUSH();
  // The range computed, [begin, end) of the n; the others are only read as neighbours.
  const uint i = p.begin + flat_invocation_id();
  const bool live = i < p.end;
  g_self = i;
  g_xi = vec3(0.0);
  ivec3 cc = ivec3(-4);
  if (live) {
    g_xi = position_at(i).xyz;
    cc = sph_cell_coords(cell_at(i), p.dims);
  }
  g_m = dfsph_mirrors(g_xi, p);
  uint candidates = 0u;
  bool overflow = false, bad = false;
  dfsph_walk(live, i, cc, sph_walls_near(g_m.axes), candidates, overflow);
  if (live) {
    const float den = dot(g_sum, g_sum) + g_sum2;
    const float f = den > 0.0 ? 1.0 / den : 0.0;
    factor[i] = f;
    bad = !sph_finite(f);
  }
  const uint over = subgroupMax(overflow ? ~i : 0u);
  const uint nonfinite = subgroupMax(bad ? ~i : 0u);
  if (subgroupElect()) {
    if (over != 0u) atomicMax(stats[kSphStatOverflow], over);
    if (nonfinite != 0u) atomicMax(stats[kSphStatNonFinite], nonfinite);
  }
  report_loop_ticks();
}
