// Parameters of the DFSPH kernels (dfsph_factor, dfsph_rate, dfsph_correct): the pressure
// solves of the dfsph model (divergence-free SPH, Bender & Koschier 2015/2017; formulas in
// engine/kernels/dfsph_kernels.h). What the host describes (DfsphParams, in double) and the
// layout the kernels read (DfsphLayout, coefficients computed once on the host, in the
// backend's precision). Shared by C++, CUDA and GLSL (engine/core/layout.h).
#ifndef MASAV_KERNELS_DFSPH_PARAMS_H
#define MASAV_KERNELS_DFSPH_PARAMS_H
#include "engine/core/layout.h"

MASAV_NAMESPACE_BEGIN

// Which constraint a solve enforces.
MASAV_ENUM_BEGIN(DfsphSolve)
// the velocity field's density change rate drho/dt = 0 (after the neighbourhood update)
MASAV_ENUMERATOR(DfsphSolve, divergence, 0)
// the density predicted at the step's end, rho + dt drho/dt, equal to rho0 (before the drift)
MASAV_ENUMERATOR(DfsphSolve, density, 1)
MASAV_ENUM_END(DfsphSolve)

// The residual words dfsph_rate adds to: per iteration slot k, a 64-bit sum (words 2k: low,
// 2k + 1: high) of each moving particle's residual in units of 2^-24 (kDfsphResidualScale),
// capped at 1 (100%): integers, so the sum is exact and independent of the order of addition.
MASAV_CONSTANT(kDfsphMaxSlots, 256)
MASAV_CONSTANT(kDfsphResidualWords, 512)
MASAV_CONSTANT(kDfsphResidualScale, 16777216)
// DfsphLayout::stop_slot when a call runs whatever the residuals hold.
MASAV_CONSTANT(kDfsphNoStop, 0xffffffff)

// What the DFSPH kernels read: the grid they walk, the spiky gradient's constant, the solve.
MASAV_REAL_LAYOUT(DfsphLayout) {
  uvec3 dims;           // the hash grid's cells per axis
  uint n;               // particles
  uint max_candidates;  // examined per particle; beyond it the kernel reports an overflow
  uint walls;           // box walls as mirror images (sph::WallMirrors)
  MASAV_ENUM(DfsphSolve) solve;
  uint slot;           // dfsph_rate: the residual slot of this iteration (< kDfsphMaxSlots)
  uint first;          // dfsph_rate: 1 on a solve's first iteration (kappa_sum is rescaled)
  uint min_neighbors;  // divergence: particles with fewer (itself included) have no residual
  uint neighbor_rows;  // 1 when the call passes neighbor_rows (see SphStepLayout)
  real_t h2;
  real_t inv_h;
  real_t grad;  // m * 45 / (pi h^4): |m grad W_spiky| = grad (1 - q)^2
  real_t rest_density;
  real_t inv_rest_density;
  real_t dt;
  real_t warm_scale;  // kappa_sum's share kept as the first iteration's start (warm start)
  real_t lo[3];
  real_t hi[3];
  // The particles computed: [begin, end) of the n (a rank's own particles; the others are only
  // read, as neighbours). From DfsphParams::step's first and count.
  uint begin;
  uint end;
  // dfsph_rate and dfsph_correct do nothing when residual slot stop_slot (not kDfsphNoStop)
  // holds at most stop_units (64 bits: stop_lo, stop_hi), i.e. when the iteration before
  // converged: the host queues several iterations before it reads a residual.
  uint stop_slot;
  uint stop_lo;
  uint stop_hi;
};

MASAV_NAMESPACE_END

#ifdef __cplusplus
#include "engine/core/buffer.h"
#include "engine/kernels/sph_kernel_params.h"

namespace masav {

MASAV_LAYOUT_CHECK(DfsphLayout<float>, 128, (dims, 0), (n, 12), (max_candidates, 16), (walls, 20),
                   (solve, 24), (slot, 28), (first, 32), (min_neighbors, 36), (neighbor_rows, 40),
                   (h2, 44), (inv_h, 48), (grad, 52), (rest_density, 56), (inv_rest_density, 60),
                   (dt, 64), (warm_scale, 68), (lo, 72), (hi, 84))
MASAV_LAYOUT_CHECK(DfsphLayout<float>, 128, (begin, 96), (end, 100), (stop_slot, 104),
                   (stop_lo, 108))
MASAV_LAYOUT_CHECK(DfsphLayout<float>, 128, (stop_hi, 112))

// One call of a DFSPH kernel. `step` gives the grid, particles, mass, h, rest density and box
// (its model must be dfsph); the rest describes the solve.
struct DfsphParams {
  SphStepParams step;
  DfsphSolve solve = DfsphSolve::density;
  double dt = 1e-3;            // s
  uint32_t slot = 0;           // residual slot (dfsph_rate)
  bool first = false;          // dfsph_rate: a solve's first iteration
  double warm_scale = 0.5;     // of kappa_sum, on the first iteration
  uint32_t min_neighbors = 0;  // divergence solve: fewer neighbours, no residual
  // dfsph_rate and dfsph_correct: do nothing if residual slot stop_slot (< kDfsphMaxSlots, before
  // `slot`) sums to at most stop_units; kDfsphNoStop: always run.
  uint32_t stop_slot = kDfsphNoStop;
  uint64_t stop_units = 0;
};

// The buffers of the DFSPH kernels: the sorted particles and grid of the last sph_density,
// whose density (the spiky kernel's, for dfsph) they read.
struct DfsphIO {
  const Buffer<Real4>* positions = nullptr;  // sorted; w = inverse mass scale
  Buffer<Real4>* velocities = nullptr;       // dfsph_rate reads them, dfsph_correct updates them
  const Buffer<Real>* density = nullptr;     // kg/m^3
  Buffer<Real>* factor = nullptr;            // dfsph_factor writes it, the others read it
  SphGridView grid;
  Buffer<Real>* kappa = nullptr;         // this iteration's p / rho^2 per particle (m^5 kg^-1 s^-2)
  Buffer<Real>* kappa_sum = nullptr;     // its sum over the solve (the next step's warm start)
  Buffer<uint32_t>* residual = nullptr;  // kDfsphResidualWords words
  Buffer<uint32_t>* stats = nullptr;     // kSphStatWords words
  const Buffer<uint32_t>* neighbor_rows = nullptr;  // optional: sph_density's masks
};

template <class F, class... Buffers>
DfsphLayout<F> device_params(const DfsphParams& p, const Buffers&... buffers) {
  constexpr double pi = 3.14159265358979323846;
  const SphStepParams& s = p.step;
  const double h = s.h;
  DfsphLayout<F> c{};
  c.dims = s.grid.dims;
  c.n = s.n;
  c.begin = s.first;
  c.end = sph_range_end(s);
  c.max_candidates = s.max_candidates;
  c.walls = s.walls ? 1u : 0u;
  c.solve = p.solve;
  c.slot = p.slot;
  c.first = p.first ? 1u : 0u;
  c.min_neighbors = p.min_neighbors;
  c.stop_slot = p.stop_slot;
  c.stop_lo = uint32_t(p.stop_units);
  c.stop_hi = uint32_t(p.stop_units >> 32);
  c.neighbor_rows = passes_neighbor_rows(buffers...) ? 1u : 0u;
  c.h2 = F(h * h);
  c.inv_h = F(1.0 / h);
  c.grad = F(s.mass * 45.0 / (pi * h * h * h * h));
  c.rest_density = F(s.rest_density);
  c.inv_rest_density = F(1.0 / s.rest_density);
  c.dt = F(p.dt);
  c.warm_scale = F(p.warm_scale);
  const double lo[3] = {s.box_min.x, s.box_min.y, s.box_min.z};
  const double hi[3] = {s.box_max.x, s.box_max.y, s.box_max.z};
  for (int a = 0; a < 3; ++a) {
    c.lo[a] = F(lo[a]);
    c.hi[a] = F(hi[a]);
  }
  return c;
}

class DeviceApi;
// Checked before any backend runs the kernel (engine/kernels/dfsph_checks.cpp).
void validate(const DeviceApi& dev, const DfsphParams& p, const Buffer<Real4>& positions,
              const Buffer<uint32_t>& cells, const Buffer<uint32_t>& cell_start,
              const Buffer<uint32_t>& cell_end, const Buffer<Real>& factor,
              const Buffer<uint32_t>& stats, const Buffer<uint32_t>* neighbor_rows);
void validate(const DeviceApi& dev, const DfsphParams& p, const Buffer<Real4>& positions,
              const Buffer<Real4>& velocities, const Buffer<Real>& density,
              const Buffer<Real>& factor, const Buffer<uint32_t>& cells,
              const Buffer<uint32_t>& cell_start, const Buffer<uint32_t>& cell_end,
              const Buffer<Real>& kappa, const Buffer<Real>& kappa_sum,
              const Buffer<uint32_t>& residual, const Buffer<uint32_t>* neighbor_rows);
void validate(const DeviceApi& dev, const DfsphParams& p, const Buffer<Real4>& positions,
              const Buffer<Real>& kappa, const Buffer<uint32_t>& cells,
              const Buffer<uint32_t>& cell_start, const Buffer<uint32_t>& cell_end,
              const Buffer<Real4>& velocities, const Buffer<uint32_t>& stats,
              const Buffer<uint32_t>* residual, const Buffer<uint32_t>* neighbor_rows);

}  // namespace masav
#endif
#endif
