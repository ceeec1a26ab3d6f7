// SPH math: the GLSL twin of engine/kernels/sph_kernels.h (smoothing kernels, Tait equation of
// state, pair terms of both pressure models, the 27-cell walk by rows, walls) and of
// engine/kernels/sph_integrate_body.h (integrator stages).
// Formulas and conventions are documented there; keep the two in step.

#include "engine/kernels/sph_kernel_params.h"

// The pressure model. A kernel that defines SPH_MODEL_SPECIALIZED before including this file
// reads it from specialization constant kSpecSphModel, which the host sets from the layout's model
// (compute/vk_kernels.cpp): the other models' arithmetic then folds away instead of running for
// every lane (a CPU driver evaluates both sides of a select, so every density term took a square
// root and every pair term divisions it did not use). Elsewhere the layout's field.
#ifdef SPH_MODEL_SPECIALIZED
layout(constant_id = kSpecSphModel) const uint SPH_MODEL = 0u;
uint sph_model(SphStepLayout c) { return SPH_MODEL; }
#else
uint sph_model(SphStepLayout c) { return c.model; }
#endif

float sph_pressure_of(float rho, SphStepLayout c) {
  if (sph_model(c) == SphPressureModel_dfsph) return 0.0;
  if (sph_model(c) == SphPressureModel_thesis) return c.eos * (rho - c.rest_density);
  const float x = rho * c.inv_rest_density;
  const float x2 = x * x;
  float p = c.eos * (x2 * x2 * x2 * x - 1.0);
  if (c.clamp_negative_pressure != 0u && p < 0.0) p = 0.0;
  return p;
}

// The pressure term's per-particle factor (sph::pressure_over_rho2): sph_forces computes it, or
// sph_density writes it into the neighbour state, with this one expression, so both give the
// same bits.
float sph_pressure_over_rho2(float pr, float rho) { return pr / (rho * rho); }

ivec3 sph_cell_coords(uint id, uvec3 dims) {
  const uint yz = dims.y * dims.z;
  return ivec3(int(id / yz), int((id % yz) / dims.z), int(id % dims.z));
}

// precise: no multiply-add fused into the term or with the sum it joins. sph_density writes its
// walk twice, with and without the wall images (sph_walk.glsl), and a GPU compiler fused the two
// copies' operations differently; unfused, a particle's density has the same bits in either.
float sph_density_term(float r2, SphStepLayout c) {
  precise float u = max(sph_model(c) != SphPressureModel_thesis ? 1.0 - sqrt(r2) * c.inv_h
                                                                : 1.0 - r2 * c.inv_h2,
                        0.0);
  precise float term = u * u * u;
  return term;
}

// Pair acceleration from neighbour (xo, vo, rho_o, p_o / rho_o^2) on (xi, vi, rho_i), d = xi - xo.
vec3 sph_pair_accel(vec3 vi, float rho_i, float pi_over_rho2, vec3 vo, float rho_o,
                    float po_over_rho2, vec3 d, float r2, SphStepLayout c) {
  const bool thesis = sph_model(c) == SphPressureModel_thesis;
  const float r = sqrt(r2);
  const float u = 1.0 - r * c.inv_h;
  vec3 a = vec3(0.0);
  if (r2 > 0.0 && sph_model(c) != SphPressureModel_dfsph) {
    float s;
    if (thesis) s = c.pressure * ((rho_o - rho_i) / rho_o) * (u * u * u);
    else s = c.pressure * (pi_over_rho2 + po_over_rho2) * (u * u);
    a = (s / r) * d;
  }
  const float w = thesis ? c.viscosity * u / rho_o : c.viscosity * u * (2.0 / (rho_i + rho_o));
  return a + w * (vo - vi);
}

// Box walls as mirror images (sph::WallMirrors): per axis the plane of the nearer wall, and in
// `axes` bit a when that wall is within h.
struct SphMirrors {
  vec3 plane;
  uint axes;
};
// sph::box_mirrors; no axes when `walls` is 0.
SphMirrors sph_box_mirrors(vec3 x, vec3 lo, vec3 hi, float h2, uint walls) {
  const vec3 to_lo = x - lo, to_hi = hi - x;
  const bvec3 low = lessThanEqual(to_lo, to_hi);
  const vec3 d = mix(to_hi, to_lo, low);
  const bvec3 near = bvec3(d.x * d.x < h2 || d.x < 0.0, d.y * d.y < h2 || d.y < 0.0,
                           d.z * d.z < h2 || d.z < 0.0);
  const uint axes = (near.x ? 1u : 0u) | (near.y ? 2u : 0u) | (near.z ? 4u : 0u);
  return SphMirrors(mix(hi, lo, low), walls != 0u ? axes : 0u);
}
SphMirrors sph_wall_mirrors(vec3 x, SphStepLayout c) {
  return sph_box_mirrors(x, vec3(c.lo[0], c.lo[1], c.lo[2]), vec3(c.hi[0], c.hi[1], c.hi[2]),
                         c.h2, c.walls);
}
// x_i minus the image of x_j across the walls in mirror set s (bits of axes).
vec3 sph_image_offset(vec3 xi, vec3 xj, SphMirrors m, uint s) {
  const vec3 direct = xi - xj, mirrored = (xi - m.plane) + (xj - m.plane);
  return mix(direct, mirrored, bvec3((s & 1u) != 0u, (s & 2u) != 0u, (s & 4u) != 0u));
}
// The 7 mirror sets are spelled out, not looped over: lavapipe counts every loop pass toward its
// iteration cap, and these run once per neighbour.
float sph_image_density_term(vec3 xi, vec3 xj, SphMirrors m, uint s, SphStepLayout c) {
  if ((s & ~m.axes) != 0u) return 0.0;
  const vec3 d = sph_image_offset(xi, xj, m, s);
  return sph_density_term(dot(d, d), c);
}
float sph_wall_image_density(vec3 xi, vec3 xj, SphMirrors m, SphStepLayout c) {
  return sph_image_density_term(xi, xj, m, 1u, c) + sph_image_density_term(xi, xj, m, 2u, c) +
         sph_image_density_term(xi, xj, m, 3u, c) + sph_image_density_term(xi, xj, m, 4u, c) +
         sph_image_density_term(xi, xj, m, 5u, c) + sph_image_density_term(xi, xj, m, 6u, c) +
         sph_image_density_term(xi, xj, m, 7u, c);
}
// The density the particle's own images add (sph::own_image_density: the density kernel's
// terms, whose gradient is exactly the own image's pair force).
float sph_own_image_density(vec3 xi, SphMirrors m, SphStepLayout c) {
  return c.density * sph_wall_image_density(xi, xi, m, c);
}
// Image of (xj, vj, rho_j, q_j = p_j / rho_j^2) in set s on (xi, vi, rho_i, q_i): the pair term
// with the opposite velocity (no-slip).
vec3 sph_image_accel_term(vec3 xi, vec3 vi, float rho_i, float q_i, vec3 xj, vec3 vj, float rho_j,
                          float q_j, SphMirrors m, uint s, SphStepLayout c) {
  if ((s & ~m.axes) != 0u) return vec3(0.0);
  const vec3 d = sph_image_offset(xi, xj, m, s);
  const float r2 = dot(d, d);
  if (!(r2 < c.h2)) return vec3(0.0);
  return sph_pair_accel(vi, rho_i, q_i, -vj, rho_j, q_j, d, r2, c);
}
vec3 sph_wall_image_accel(vec3 xi, vec3 vi, float rho_i, float q_i, vec3 xj, vec3 vj,
                          float rho_j, float q_j, SphMirrors m, SphStepLayout c) {
  vec3 a = sph_image_accel_term(xi, vi, rho_i, q_i, xj, vj, rho_j, q_j, m, 1u, c);
  a += sph_image_accel_term(xi, vi, rho_i, q_i, xj, vj, rho_j, q_j, m, 2u, c);
  a += sph_image_accel_term(xi, vi, rho_i, q_i, xj, vj, rho_j, q_j, m, 3u, c);
  a += sph_image_accel_term(xi, vi, rho_i, q_i, xj, vj, rho_j, q_j, m, 4u, c);
  a += sph_image_accel_term(xi, vi, rho_i, q_i, xj, vj, rho_j, q_j, m, 5u, c);
  a += sph_image_accel_term(xi, vi, rho_i, q_i, xj, vj, rho_j, q_j, m, 6u, c);
  a += sph_image_accel_term(xi, vi, rho_i, q_i, xj, vj, rho_j, q_j, m, 7u, c);
  return a;
}

vec3 sph_total_accel(vec3 pair, float inv_mass, SphStepLayout c) {
  if (!(inv_mass > 0.0)) return vec3(0.0);
  return inv_mass * pair + vec3(c.gravity[0], c.gravity[1], c.gravity[2]);
}

bool sph_wall_response(inout vec3 x, inout vec3 v, vec3 lo, vec3 hi, float restitution,
                       float tangential_damping) {
  bvec3 hit = bvec3(false);
  for (int a = 0; a < 3; ++a) {
    LOOP_TICK();
    if (x[a] < lo[a]) {
      x[a] = lo[a];
      if (v[a] < 0.0) v[a] = -restitution * v[a];
      hit[a] = true;
    } else if (x[a] > hi[a]) {
      x[a] = hi[a];
      if (v[a] > 0.0) v[a] = -restitution * v[a];
      hit[a] = true;
    }
  }
  const bool any_hit = any(hit);
  if (any_hit && tangential_damping > 0.0) {
    const float keep = 1.0 - tangential_damping;
    for (int a = 0; a < 3; ++a) {
      LOOP_TICK();
      if (!hit[a]) v[a] = keep * v[a];
    }
  }
  return any_hit;
}

bool sph_op_ends_step(uint op) {
  return op == SphStageOp_euler || op == SphStageOp_symplectic_euler || op == SphStageOp_rk4_final ||
         op == SphStageOp_kick_drift || op == SphStageOp_drift;
}

void sph_integrate_stage(uint op, float dt, vec3 x0, vec3 v0, vec3 vk, vec3 a, out vec3 x_out,
                         out vec3 v_out, inout vec3 sx, inout vec3 sv) {
  const float half_dt = 0.5 * dt;
  if (op == SphStageOp_euler) {
    x_out = x0 + dt * v0;
    v_out = v0 + dt * a;
  } else if (op == SphStageOp_symplectic_euler) {
    v_out = v0 + dt * a;
    x_out = x0 + dt * v_out;
  } else if (op == SphStageOp_rk4_stage1) {
    sx = v0;
    sv = a;
    x_out = x0 + half_dt * v0;
    v_out = v0 + half_dt * a;
  } else if (op == SphStageOp_rk4_stage2) {
    sx = sx + 2.0 * vk;
    sv = sv + 2.0 * a;
    x_out = x0 + half_dt * vk;
    v_out = v0 + half_dt * a;
  } else if (op == SphStageOp_rk4_stage3) {
    sx = sx + 2.0 * vk;
    sv = sv + 2.0 * a;
    x_out = x0 + dt * vk;
    v_out = v0 + dt * a;
  } else if (op == SphStageOp_rk4_final) {
    const float sixth = dt / 6.0;
    x_out = x0 + sixth * (sx + vk);
    v_out = v0 + sixth * (sv + a);
  } else if (op == SphStageOp_kick_drift) {
    v_out = v0 + half_dt * a;
    x_out = x0 + dt * v_out;
  } else if (op == SphStageOp_accelerate) {
    x_out = x0;
    v_out = v0 + dt * a;
  } else if (op == SphStageOp_drift) {
    x_out = x0 + dt * v0;
    v_out = v0;
  } else {
    x_out = x0;
    v_out = v0 + half_dt * a;
  }
}

bool sph_finite(vec3 v) { return !any(isnan(v)) && !any(isinf(v)); }
bool sph_finite(float v) { return !isnan(v) && !isinf(v); }
