#pragma once
// The SPH integrator's per-particle body, shared by the CPU reference (T = double) and CUDA
// (T = float): one stage of the step (SphStageOp), then the box walls' response, and what the
// particle adds to the step statistics. shaders/sph_integrate.comp and shaders/common/sph.glsl
// are the GLSL twins.
#include "engine/kernels/sph_kernels.h"

namespace masav::sph {

// Box walls: a particle past a wall is put back on it; its normal velocity, if it points out,
// is reversed and scaled by `restitution`; its tangential velocity is scaled by
// (1 - tangential_damping). Returns true if the particle touched a wall.
template <class T>
MASAV_HD inline bool wall_response(V3<T>& x, V3<T>& v, const T lo[3], const T hi[3], T restitution,
                                   T tangential_damping) {
  T* xp[3] = {&x.x, &x.y, &x.z};
  T* vp[3] = {&v.x, &v.y, &v.z};
  bool hit[3] = {false, false, false};
  for (int a = 0; a < 3; ++a) {
    if (*xp[a] < lo[a]) {
      *xp[a] = lo[a];
      if (*vp[a] < T(0)) *vp[a] = -restitution * *vp[a];
      hit[a] = true;
    } else if (*xp[a] > hi[a]) {
      *xp[a] = hi[a];
      if (*vp[a] > T(0)) *vp[a] = -restitution * *vp[a];
      hit[a] = true;
    }
  }
  const bool any = hit[0] || hit[1] || hit[2];
  if (any && tangential_damping > T(0)) {
    const T keep = T(1) - tangential_damping;
    for (int a = 0; a < 3; ++a)
      if (!hit[a]) *vp[a] = keep * *vp[a];
  }
  return any;
}

// Integrator stages (SphStageOp):
//   euler             x1 = x0 + dt v0, v1 = v0 + dt a(x0, v0)
//   symplectic_euler  v1 = v0 + dt a, x1 = x0 + dt v1
//   rk4_stage1        k1 = (v0, a); stage 2 state y0 + dt/2 k1
//   rk4_stage2        k2 = (vk, a); stage 3 state y0 + dt/2 k2
//   rk4_stage3        k3 = (vk, a); stage 4 state y0 + dt k3
//   rk4_final         y1 = y0 + dt/6 (k1 + 2 k2 + 2 k3 + k4)
//   kick_drift        v_half = v0 + dt/2 a, x1 = x0 + dt v_half
//   kick              v1 = v_half + dt/2 a(x1)
//   accelerate        v1 = v0 + dt a (dfsph's prediction before its density solve)
//   drift             x1 = x0 + dt v0, v1 = v0 (dfsph, after its density solve)
MASAV_HD inline bool op_ends_step(SphStageOp op) {
  return op == SphStageOp::euler || op == SphStageOp::symplectic_euler ||
         op == SphStageOp::rk4_final || op == SphStageOp::kick_drift || op == SphStageOp::drift;
}

// One particle's stage update. x0/v0: step-start state; vk: stage velocity (RK4); a: stage
// acceleration; sx/sv: RK4 running sums (in: previous, out: updated) or, for kick_drift, sv
// receives the predicted end-of-step velocity v_half + dt/2 a that the viscosity term uses.
template <class T>
MASAV_HD inline void integrate_stage(SphStageOp op, T dt, V3<T> x0, V3<T> v0, V3<T> vk, V3<T> a,
                                     V3<T>& x_out, V3<T>& v_out, V3<T>& sx, V3<T>& sv) {
  const T half = T(0.5) * dt;
  switch (op) {
    case SphStageOp::euler:
      x_out = x0 + dt * v0;
      v_out = v0 + dt * a;
      break;
    case SphStageOp::symplectic_euler:
      v_out = v0 + dt * a;
      x_out = x0 + dt * v_out;
      break;
    case SphStageOp::rk4_stage1:
      sx = v0;
      sv = a;
      x_out = x0 + half * v0;
      v_out = v0 + half * a;
      break;
    case SphStageOp::rk4_stage2:
      sx = sx + T(2) * vk;
      sv = sv + T(2) * a;
      x_out = x0 + half * vk;
      v_out = v0 + half * a;
      break;
    case SphStageOp::rk4_stage3:
      sx = sx + T(2) * vk;
      sv = sv + T(2) * a;
      x_out = x0 + dt * vk;
      v_out = v0 + dt * a;
      break;
    case SphStageOp::rk4_final: {
      const T sixth = dt / T(6);
      x_out = x0 + sixth * (sx + vk);
      v_out = v0 + sixth * (sv + a);
      break;
    }
    case SphStageOp::kick_drift:
      v_out = v0 + half * a;
      x_out = x0 + dt * v_out;
      break;
    case SphStageOp::accelerate:
      x_out = x0;
      v_out = v0 + dt * a;
      break;
    case SphStageOp::drift:
      x_out = x0 + dt * v0;
      v_out = v0;
      break;
    case SphStageOp::kick:
    default:
      x_out = x0;
      v_out = v0 + half * a;
      break;
  }
}

// The stage update of one particle, then (for ops that end a step) the box walls; kick_drift
// also predicts the end-of-step velocity into sv. Returns false if the particle lies outside
// the box afterwards (walls off, or a non-finite position).
template <class T>
MASAV_HD inline bool stage_particle(const SphIntegrateLayout<T>& p, V3<T> x0, V3<T> v0, V3<T> vk,
                                    V3<T> a, V3<T>& x_out, V3<T>& v_out, V3<T>& sx, V3<T>& sv) {
  integrate_stage(p.op, p.dt, x0, v0, vk, a, x_out, v_out, sx, sv);
  if (op_ends_step(p.op) && p.walls)
    wall_response(x_out, v_out, p.lo, p.hi, p.restitution, p.tangential_damping);
  if (p.op == SphStageOp::kick_drift) sv = v_out + (T(0.5) * p.dt) * a;
  return x_out.x >= p.lo[0] && x_out.x <= p.hi[0] && x_out.y >= p.lo[1] && x_out.y <= p.hi[1] &&
         x_out.z >= p.lo[2] && x_out.z <= p.hi[2];
}

// What one particle's stage adds to the step statistics (SphStat).
template <class T>
struct StageReport {
  T speed2 = T(0);  // |v_out|^2
  T disp2 = T(0);   // |x_out - x0|^2
  bool non_finite = false;
  bool outside = false;  // outside the box after a step-ending stage
};

// sph_integrate's whole per-particle body: reads particle i's state, runs stage_particle, writes
// the outputs. Buffers the op does not use may be null (x0 and x_out for kick and accelerate,
// vk outside RK4
// stages 2-4, the sums outside RK4 and kick_drift).
template <class T>
MASAV_HD inline StageReport<T> integrate_particle(uint32_t i, const SphIntegrateLayout<T>& p,
                                                  const hd::V4<T>* x0, const hd::V4<T>* v0,
                                                  const hd::V4<T>* vk, const hd::V4<T>* accel,
                                                  hd::V4<T>* x_out, hd::V4<T>* v_out,
                                                  hd::V4<T>* sum_x, hd::V4<T>* sum_v) {
  const bool kick = p.op == SphStageOp::kick || p.op == SphStageOp::accelerate;  // no positions
  const bool rk4 = p.op >= SphStageOp::rk4_stage1 && p.op <= SphStageOp::rk4_final;
  const bool uses_vk = rk4 && p.op != SphStageOp::rk4_stage1;
  const hd::V4<T> xw = kick ? hd::V4<T>{T(0), T(0), T(0), T(0)} : x0[i];
  const V3<T> x = xyz(xw), v = xyz(v0[i]);
  const V3<T> kv = uses_vk ? xyz(vk[i]) : v;
  const V3<T> a = xyz(accel[i]);
  V3<T> sx = rk4 ? xyz(sum_x[i]) : V3<T>{T(0), T(0), T(0)};
  V3<T> sv = rk4 ? xyz(sum_v[i]) : V3<T>{T(0), T(0), T(0)};
  V3<T> xn{}, vn{};
  const bool inside = stage_particle(p, x, v, kv, a, xn, vn, sx, sv);
  if (!kick) x_out[i] = hd::V4<T>{xn.x, xn.y, xn.z, xw.w};
  v_out[i] = hd::V4<T>{vn.x, vn.y, vn.z, T(0)};
  if (rk4) sum_x[i] = hd::V4<T>{sx.x, sx.y, sx.z, T(0)};
  if (rk4 || p.op == SphStageOp::kick_drift) sum_v[i] = hd::V4<T>{sv.x, sv.y, sv.z, T(0)};
  StageReport<T> r;
  if (!finite3(vn) || (!kick && !finite3(xn))) {
    r.non_finite = true;
    return r;
  }
  r.speed2 = dot(vn, vn);
  if (!kick) {
    const V3<T> d = xn - x;
    r.disp2 = dot(d, d);
    r.outside = op_ends_step(p.op) && !inside;
  }
  return r;
}

}  // namespace masav::sph
