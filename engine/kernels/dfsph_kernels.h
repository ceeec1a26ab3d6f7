#pragma once
// DFSPH math shared by the CPU reference (T = double) and CUDA (T = float): the per-particle
// bodies of dfsph_factor, dfsph_rate and dfsph_correct. shaders/common/dfsph.glsl is the GLSL
// twin. Divergence-free SPH (Bender & Koschier, SCA 2015 / TVCG 2017) in the form
//
//   density   rho_i      = sum_j m W(r_ij) (spiky; sph_density with the dfsph model)
//   factor    f_i        = 1 / (|sum_j m grad W_ij|^2 + sum_j |m grad W_ij|^2)
//   rate      drho_i/dt  = sum_j m grad W_ij . (v_i - v_j)
//   kappa     k_i        = f_i (rho_i + dt drho_i/dt - rho0)^+ / dt^2    (density solve)
//                        = f_i (drho_i/dt)^+ / dt                        (divergence solve)
//   correct   v_i       -= dt w_i sum_j (k_i + k_j) m grad W_ij
//
// with grad W the spiky kernel's gradient, the one whose kernel gives the density (so a solve
// predicts the very density it corrects), w_i the inverse mass scale (0 pinned), and k the
// pressure over density squared, p / rho^2 (m^5 kg^-1 s^-2). The sums over j take the
// neighbours within h and, near a box wall, their mirror images (sph::WallMirrors) and the
// particle's own: an image carries its particle's kappa and the mirrored velocity (normal
// component reversed), so a particle approaching a wall compresses against its own image and
// the correction pushes it back -- the wall needs no particles of its own. The factor is the
// Jacobi step of the linear system dt^2 A k = residual: the particle's own images count twice in
// the gradient sum (see dfsph_factor_of), a neighbour's images as if they moved like neighbours
// (a larger diagonal: a smaller, safe step). Only compression is corrected
// (the ^+): a free surface's low density asks for no tension. In the divergence solve a particle
// with fewer than min_neighbors neighbours (a splash) has no residual.
#include <cstdint>

#include "engine/core/hd.h"
#include "engine/kernels/dfsph_params.h"
#include "engine/kernels/sph_kernels.h"

namespace masav::sph {

// The factor s of m grad_i W_spiky(x_i - x_j) = s d, d = x_i - x_j, for 0 < r^2 < h^2.
template <class T>
MASAV_HD inline T dfsph_gradient_scale(T r2, const DfsphLayout<T>& c) {
  const T r = sqrt(r2);
  const T u = T(1) - r * c.inv_h;
  return -(c.grad * u * u) / r;
}

// m grad_i W_spiky(x_i - x_j), d = x_i - x_j, for r^2 < h^2; 0 at r = 0 (no direction).
template <class T>
MASAV_HD inline V3<T> dfsph_gradient(V3<T> d, T r2, const DfsphLayout<T>& c) {
  if (!(r2 > T(0))) return V3<T>{T(0), T(0), T(0)};
  return dfsph_gradient_scale(r2, c) * d;
}

// The velocity of an image in mirror set s: the components across the reflecting walls reversed.
template <class T>
MASAV_HD inline V3<T> mirror_velocity(V3<T> v, uint32_t s) {
  return V3<T>{(s & 1u) ? -v.x : v.x, (s & 2u) ? -v.y : v.y, (s & 4u) ? -v.z : v.z};
}

template <class T>
MASAV_HD inline WallMirrors<T> dfsph_mirrors(V3<T> x, const DfsphLayout<T>& c) {
  return c.walls ? box_mirrors(x, c.lo, c.hi, c.h2) : WallMirrors<T>{};
}

// A residual (relative, >= 0) in the integer units dfsph_rate sums: capped at 1; NaN counts 1.
template <class T>
MASAV_HD inline uint32_t dfsph_residual_units(T r) {
  r = r < T(1) ? r : T(1);
  r = r > T(0) ? r : T(0);
  return uint32_t(r * T(kDfsphResidualScale));
}

// Whether a dfsph_rate or dfsph_correct call does nothing (DfsphLayout::stop_slot): the
// iteration before it converged. residual: the kDfsphResidualWords words.
template <class T>
MASAV_HD inline bool dfsph_stopped(const DfsphLayout<T>& c, const uint32_t* residual) {
  if (c.stop_slot == kDfsphNoStop) return false;
  const uint32_t lo = residual[2 * c.stop_slot], hi = residual[2 * c.stop_slot + 1];
  return hi < c.stop_hi || (hi == c.stop_hi && lo <= c.stop_lo);
}

// Each body takes walk(visit), which calls visit(j) for every candidate neighbour j of the
// particle (itself included; the visitor tests the distance), and pos_at(j) etc. that read
// sorted particle j: the GPU walks the 27 cells (sph::walk_candidates), the CPU reference its
// neighbour lists.

// The tails of the bodies below, from their sums over the neighbours and images (the CPU
// reference also forms those sums from gradients it keeps, engine/cpu/cpu_dfsph_terms.h).

// f_i from sum = sum_j m grad W_ij (own images twice) and sum2 = sum_j |m grad W_ij|^2.
template <class T>
MASAV_HD inline T dfsph_factor_from(V3<T> sum, T sum2) {
  const T den = dot(sum, sum) + sum2;
  return den > T(0) ? T(1) / den : T(0);
}

template <class T>
struct DfsphRate {
  T kappa;     // k_i of this iteration
  T residual;  // relative: (rho* - rho0)^+ / rho0, or dt (drho/dt)^+ / rho0
};

// Kappa and residual from div = drho_i/dt and the candidates within h (itself included).
template <class T>
MASAV_HD inline DfsphRate<T> dfsph_rate_from(T div, uint32_t neighbors, T rho, T factor,
                                             const DfsphLayout<T>& c) {
  DfsphRate<T> r{T(0), T(0)};
  if (c.solve == DfsphSolve::density) {
    T excess = rho + c.dt * div - c.rest_density;
    excess = excess > T(0) ? excess : T(0);
    r.kappa = excess * factor / (c.dt * c.dt);
    r.residual = excess * c.inv_rest_density;
  } else {
    T rate = neighbors >= c.min_neighbors ? div : T(0);
    rate = rate > T(0) ? rate : T(0);
    r.kappa = rate * factor / c.dt;
    r.residual = c.dt * rate * c.inv_rest_density;
  }
  return r;
}

// The velocity change (before the inverse mass scale) from acc = sum_j (k_i + k_j) m grad W_ij.
// The warm start (first = 1) applies warm_scale of the last solve's kappa sum.
template <class T>
MASAV_HD inline V3<T> dfsph_correction_from(V3<T> acc, const DfsphLayout<T>& c) {
  return (c.first ? -c.dt * c.warm_scale : -c.dt) * acc;
}

// dfsph_factor: f_i of particle `self` at xi.
template <class T, class Walk, class PosAt>
MASAV_HD inline T dfsph_factor_of(uint32_t self, V3<T> xi, const DfsphLayout<T>& c, Walk&& walk,
                                  PosAt&& pos_at) {
  const WallMirrors<T> m = dfsph_mirrors(xi, c);
  V3<T> sum{T(0), T(0), T(0)};
  T sum2 = T(0);
  auto add = [&](V3<T> d, T r2) {
    const V3<T> g = dfsph_gradient(d, r2, c);
    sum = sum + g;
    sum2 += dot(g, g);
  };
  // An own image moves with the particle (mirrored) and carries its kappa: it enters its
  // velocity change twice (k_i + k_i) and its density change twice (v_i - R v_i is twice the
  // normal velocity), with no neighbour response of its own.
  auto add_own = [&](V3<T> d, T r2) { sum = sum + T(2) * dfsph_gradient(d, r2, c); };
  walk([&](uint32_t j) {
    const V3<T> xj = pos_at(j);
    const V3<T> d = xi - xj;
    const T r2 = dot(d, d);
    if (!(r2 < c.h2)) return;
    if (j != self) add(d, r2);
    if (m.axes) {
      if (j == self)
        for_each_wall_image(xi, xj, m, c.h2, add_own);
      else
        for_each_wall_image(xi, xj, m, c.h2, add);
    }
  });
  return dfsph_factor_from(sum, sum2);
}

// dfsph_rate: particle `self`'s residual and kappa from the velocities vel_at(j).
template <class T, class Walk, class PosAt, class VelAt>
MASAV_HD inline DfsphRate<T> dfsph_rate_of(uint32_t self, V3<T> xi, V3<T> vi, T rho, T factor,
                                           const DfsphLayout<T>& c, Walk&& walk, PosAt&& pos_at,
                                           VelAt&& vel_at) {
  const WallMirrors<T> m = dfsph_mirrors(xi, c);
  T div = T(0);
  uint32_t neighbors = 0;
  walk([&](uint32_t j) {
    const V3<T> xj = pos_at(j);
    const V3<T> d = xi - xj;
    const T r2 = dot(d, d);
    if (!(r2 < c.h2)) return;
    ++neighbors;
    const V3<T> vj = j == self ? vi : vel_at(j);
    if (j != self) div += dot(dfsph_gradient(d, r2, c), vi - vj);
    if (m.axes)
      for_each_wall_image_set(xi, xj, m, c.h2, [&](V3<T> di, T ri2, uint32_t s) {
        div += dot(dfsph_gradient(di, ri2, c), vi - mirror_velocity(vj, s));
      });
  });
  return dfsph_rate_from(div, neighbors, rho, factor, c);
}

// The kappa sum dfsph_rate keeps: a solve's first iteration starts from warm_scale of the last
// solve's sum (the warm start dfsph_correct applied before it).
template <class T>
MASAV_HD inline T dfsph_kappa_sum(T previous, T kappa, const DfsphLayout<T>& c) {
  return (c.first ? c.warm_scale * previous : previous) + kappa;
}

// dfsph_correct: the velocity change of particle `self` (before its inverse mass scale) from
// the kappas kappa_at(j).
template <class T, class Walk, class PosAt, class KappaAt>
MASAV_HD inline V3<T> dfsph_correction_of(uint32_t self, V3<T> xi, T kappa_i,
                                          const DfsphLayout<T>& c, Walk&& walk, PosAt&& pos_at,
                                          KappaAt&& kappa_at) {
  const WallMirrors<T> m = dfsph_mirrors(xi, c);
  V3<T> acc{T(0), T(0), T(0)};
  walk([&](uint32_t j) {
    const V3<T> xj = pos_at(j);
    const V3<T> d = xi - xj;
    const T r2 = dot(d, d);
    if (!(r2 < c.h2)) return;
    const T k = kappa_i + (j == self ? kappa_i : kappa_at(j));
    if (j != self) acc = acc + k * dfsph_gradient(d, r2, c);
    if (m.axes)
      for_each_wall_image(xi, xj, m, c.h2,
                          [&](V3<T> di, T ri2) { acc = acc + k * dfsph_gradient(di, ri2, c); });
  });
  return dfsph_correction_from(acc, c);
}

}  // namespace masav::sph
