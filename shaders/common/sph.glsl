// SPH math: the GLSL twin of engine/kernels/sph_kernels.h (smoothing kernels, Tait equation of
// state, pair terms of both pressure models, the 27-cell walk by rows, walls, integrator stages).
// Formulas and conventions are documented there; keep the two in step.

#include "engine/kernels/sph_kernel_params.h"

float sph_pressure_of(float rho, SphStepLayout c) {
  if (c.model == SphPressureModel_thesis) return c.eos * (rho - c.rest_density);
  const float x = rho * c.inv_rest_density;
  const float x2 = x * x;
  float p = c.eos * (x2 * x2 * x2 * x - 1.0);
  if (c.clamp_negative_pressure != 0u && p < 0.0) p = 0.0;
  return p;
}

ivec3 sph_cell_coords(uint id, uvec3 dims) {
  const uint yz = dims.y * dims.z;
  return ivec3(int(id / yz), int((id % yz) / dims.z), int(id % dims.z));
}

// Semi-analytic box walls (sph::wall_density in engine/kernels/sph_kernels.h).
float sph_wall_density_fraction(float q) {
  const float q2 = q * q;
  const float f =
      q * (1.0 + q2 * (-4.0 / 3.0 + q2 * (6.0 / 5.0 + q2 * (-4.0 / 7.0 + q2 * (1.0 / 9.0)))));
  return 0.5 - (315.0 / 256.0) * f;
}
float sph_wall_density_slope(float q) {
  const float u = 1.0 - q * q;
  return (315.0 / 256.0) * (u * u) * (u * u);
}
float sph_wall_density(vec3 x, SphStepLayout c, out vec3 push) {
  float f[6], slope[6];
  float keep = 1.0;
  for (int k = 0; k < 6; ++k) {
    LOOP_TICK();
    const int a = k >> 1;
    const float d = (k & 1) != 0 ? c.hi[a] - x[a] : x[a] - c.lo[a];
    const float q = (max(d, 0.0) + c.wall_offset) * c.inv_h;
    f[k] = q < 1.0 ? sph_wall_density_fraction(q) : 0.0;
    slope[k] = q < 1.0 ? sph_wall_density_slope(q) : 0.0;
    keep *= 1.0 - f[k];
  }
  push = vec3(0.0);
  for (int k = 0; k < 6; ++k) {
    LOOP_TICK();
    float others = 1.0;
    for (int m = 0; m < 6; ++m) {
      LOOP_TICK();
      if (m != k) others *= 1.0 - f[m];
    }
    push[k >> 1] += ((k & 1) != 0 ? -slope[k] : slope[k]) * others;
  }
  return 1.0 - keep;
}

// No-slip walls (sph::wall_viscous_weight).
float sph_wall_viscous_weight(vec3 x, SphStepLayout c) {
  float w = 0.0;
  for (int k = 0; k < 6; ++k) {
    LOOP_TICK();
    const int a = k >> 1;
    const float d = (k & 1) != 0 ? c.hi[a] - x[a] : x[a] - c.lo[a];
    const float q = (max(d, 0.0) + c.wall_offset) * c.inv_h;
    if (q < 1.0) {
      const float u = 1.0 - q;
      w += u * u * u * (1.0 + q);
    }
  }
  return w;
}

float sph_density_term(float r2, SphStepLayout c) {
  const float u = max(1.0 - r2 * c.inv_h2, 0.0);
  return u * u * u;
}

// Pair acceleration from neighbour (xo, vo, rho_o, p_o / rho_o^2) on (xi, vi, rho_i), d = xi - xo.
vec3 sph_pair_accel(vec3 vi, float rho_i, float pi_over_rho2, vec3 vo, float rho_o,
                    float po_over_rho2, vec3 d, float r2, SphStepLayout c) {
  const bool thesis = c.model == SphPressureModel_thesis;
  const float r = sqrt(r2);
  const float u = 1.0 - r * c.inv_h;
  vec3 a = vec3(0.0);
  if (r2 > 0.0) {
    float s;
    if (thesis) s = c.pressure * ((rho_o - rho_i) / rho_o) * (u * u * u);
    else s = c.pressure * (pi_over_rho2 + po_over_rho2) * (u * u);
    a = (s / r) * d;
  }
  const float w = thesis ? c.viscosity * u / rho_o : c.viscosity * u * (2.0 / (rho_i + rho_o));
  return a + w * (vo - vi);
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
         op == SphStageOp_kick_drift;
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
  } else {
    x_out = x0;
    v_out = v0 + half_dt * a;
  }
}

bool sph_finite(vec3 v) { return !any(isnan(v)) && !any(isinf(v)); }
bool sph_finite(float v) { return !isnan(v) && !isinf(v); }
