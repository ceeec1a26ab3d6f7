#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_arithmetic : require
// One integrator stage per particle (op: Euler, symplectic Euler, RK4 stages, leapfrog kick /
// drift), then the box walls for ops that end a step; reports the largest speed and drift,
// non-finite values and particles outside the box. Twin of sph::stage_particle. Output buffers
// may alias inputs: each invocation reads its own element before writing it (no `restrict`).
#include "kernel_base.glsl"

// What the kernel only reads are uniform texel buffers (compute/vk_kernels.cpp): lavapipe loads
// a storage buffer's element in a loop over the lanes, a texel with plain loads.
layout(binding = 1) uniform samplerBuffer x0_texels;     // rgba32f
layout(binding = 2) uniform samplerBuffer v0_texels;     // rgba32f
layout(binding = 3) uniform samplerBuffer vk_texels;     // rgba32f
layout(binding = 4) uniform samplerBuffer accel_texels;  // rgba32f
layout(std430, binding = 5) writeonly buffer XOut { vec4 x_out[]; };
layout(std430, binding = 6) writeonly buffer VOut { vec4 v_out[]; };
layout(std430, binding = 7) buffer SumX { vec4 sum_x[]; };
layout(std430, binding = 8) buffer SumV { vec4 sum_v[]; };
layout(std430, binding = 9) buffer Stats { uint stats[]; };
// The dt of a stage recorded for replay (SphIntegrateLayout::dt_slot; compute/vk_stream.h).
layout(std430, binding = 10) readonly buffer DtTable { float dt_table[]; };

#include "sph.glsl"

MASAV_PUSH(SphIntegrateLayout);

void main() {
  MASAV_LOAD_PUSH();
  const float dt = p.dt_slot == kSphDtInline ? p.dt : dt_table[p.dt_slot];
  // The range stepped, [first, end) of the n (a rank's own particles); the others are left
  // as they are.
  const uint i = p.first + flat_invocation_id();
  const bool live = i < p.end;
  const uint op = p.op;
  const bool kick = op == SphStageOp_kick || op == SphStageOp_accelerate;  // no positions
  const bool rk4 = op >= SphStageOp_rk4_stage1 && op <= SphStageOp_rk4_final;
  float speed2 = 0.0, disp2 = 0.0;
  bool bad = false, outside = false;
  if (live) {
    const vec4 xw = kick ? vec4(0.0) : texelFetch(x0_texels, int(i));
    const vec3 x = xw.xyz;
    const vec3 v = texelFetch(v0_texels, int(i)).xyz;
    const vec3 kv = rk4 && op != SphStageOp_rk4_stage1 ? texelFetch(vk_texels, int(i)).xyz : v;
    const vec3 a = texelFetch(accel_texels, int(i)).xyz;
    vec3 sx = rk4 ? sum_x[i].xyz : vec3(0.0);
    vec3 sv = rk4 ? sum_v[i].xyz : vec3(0.0);
    vec3 xn, vn;
    sph_integrate_stage(op, dt, x, v, kv, a, xn, vn, sx, sv);
    const vec3 lo = vec3(p.lo[0], p.lo[1], p.lo[2]), hi = vec3(p.hi[0], p.hi[1], p.hi[2]);
    if (sph_op_ends_step(op) && p.walls != 0u)
      sph_wall_response(xn, vn, lo, hi, p.restitution, p.tangential_damping);
    if (op == SphStageOp_kick_drift) sv = vn + (0.5 * dt) * a;
    if (!kick) x_out[i] = vec4(xn, xw.w);
    v_out[i] = vec4(vn, 0.0);
    if (rk4) sum_x[i] = vec4(sx, 0.0);
    if (rk4 || op == SphStageOp_kick_drift) sum_v[i] = vec4(sv, 0.0);
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
    atomicMax(stats[kSphStatMaxSpeed2], max_s2);
    atomicMax(stats[kSphStatMaxDisp2], max_d2);
    if (nonfinite != 0u) atomicMax(stats[kSphStatNonFinite], nonfinite);
    if (out_count != 0u) atomicAdd(stats[kSphStatOutside], out_count);
  }
  report_loop_ticks();
}
