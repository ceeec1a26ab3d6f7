#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_arithmetic : require
// One integrator stage per particle (op: Euler, symplectic Euler, RK4 stages, leapfrog kick /
// drift), then the box walls for ops that end a step; reports the largest speed and drift,
// non-finite values and particles outside the box. Twin of sph::stage_particle. Output buffers
// may alias inputs: each invocation reads its own element before writing it (no `restrict`).
#include "kernel_base.glsl"

layout(std430, binding = 1) readonly buffer X0 { vec4 x0[]; };
layout(std430, binding = 2) readonly buffer V0 { vec4 v0[]; };
layout(std430, binding = 3) readonly buffer Vk { vec4 vk[]; };
layout(std430, binding = 4) readonly buffer Accel { vec4 accel[]; };
layout(std430, binding = 5) writeonly buffer XOut { vec4 x_out[]; };
layout(std430, binding = 6) writeonly buffer VOut { vec4 v_out[]; };
layout(std430, binding = 7) buffer SumX { vec4 sum_x[]; };
layout(std430, binding = 8) buffer SumV { vec4 sum_v[]; };
layout(std430, binding = 9) buffer Stats { uint stats[]; };

#include "sph.glsl"

layout(push_constant) uniform Push {
  vec4 lo_dt;          // box min, dt
  vec4 hi_restitution; // box max, restitution
  float tangential_damping;
  uint op;
  uint walls;
  uint n;
  uint use_vk;         // 1: read vk (RK4 stages 2-4); 0: the stage velocity is v0
} pc;

void main() {
  const uint i = flat_invocation_id();
  const bool live = i < pc.n;
  const uint op = pc.op;
  const bool kick = op == SPH_OP_KICK;
  const bool rk4 = op >= SPH_OP_RK4_STAGE1 && op <= SPH_OP_RK4_FINAL;
  float speed2 = 0.0, disp2 = 0.0;
  bool bad = false, outside = false;
  if (live) {
    const vec4 xw = kick ? vec4(0.0) : x0[i];
    const vec3 x = xw.xyz;
    const vec3 v = v0[i].xyz;
    const vec3 kv = pc.use_vk != 0u ? vk[i].xyz : v;
    const vec3 a = accel[i].xyz;
    vec3 sx = rk4 ? sum_x[i].xyz : vec3(0.0);
    vec3 sv = rk4 ? sum_v[i].xyz : vec3(0.0);
    vec3 xn, vn;
    sph_integrate_stage(op, pc.lo_dt.w, x, v, kv, a, xn, vn, sx, sv);
    const vec3 lo = pc.lo_dt.xyz, hi = pc.hi_restitution.xyz;
    if (sph_op_ends_step(op) && pc.walls != 0u)
      sph_wall_response(xn, vn, lo, hi, pc.hi_restitution.w, pc.tangential_damping);
    if (op == SPH_OP_KICK_DRIFT) sv = vn + (0.5 * pc.lo_dt.w) * a;
    if (!kick) x_out[i] = vec4(xn, xw.w);
    v_out[i] = vec4(vn, 0.0);
    if (rk4) sum_x[i] = vec4(sx, 0.0);
    if (rk4 || op == SPH_OP_KICK_DRIFT) sum_v[i] = vec4(sv, 0.0);
    bad = !sph_finite(vn) || (!kick && !sph_finite(xn));
    if (!bad) {
      speed2 = dot(vn, vn);
      if (!kick) {
        const vec3 d = xn - x;
        disp2 = dot(d, d);
        outside = sph_op_ends_step(op) &&
                  !(all(greaterThanEqual(xn, lo)) && all(lessThanEqual(xn, hi)));
      }
    }
  }
  const uint max_s2 = subgroupMax(floatBitsToUint(speed2));
  const uint max_d2 = subgroupMax(floatBitsToUint(disp2));
  const uint nonfinite = subgroupMax(bad ? ~i : 0u);
  const uint out_count = subgroupAdd(outside ? 1u : 0u);
  if (subgroupElect()) {
    atomicMax(stats[SPH_STAT_MAX_SPEED2], max_s2);
    atomicMax(stats[SPH_STAT_MAX_DISP2], max_d2);
    if (nonfinite != 0u) atomicMax(stats[SPH_STAT_NON_FINITE], nonfinite);
    if (out_count != 0u) atomicAdd(stats[SPH_STAT_OUTSIDE], out_count);
  }
  report_loop_ticks();
}
