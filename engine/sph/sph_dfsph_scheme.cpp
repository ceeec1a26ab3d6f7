// SphDfsphScheme: the step of the dfsph pressure model (divergence-free SPH, Bender & Koschier;
// formulas in engine/kernels/dfsph_kernels.h). One step of dt from a state whose velocities are
// divergence-free and whose density and factor belong to its positions:
//   1. viscosity and gravity at the step's start (sph_forces; dfsph adds no pressure there),
//      v* = v + dt a (sph_integrate: accelerate);
//   2. the density solve: v* corrected until the density it predicts at the step's end,
//      rho + dt drho/dt, is within dfsph_density_error of rho0 on average;
//   3. x1 = x + dt v* with the box walls (sph_integrate: drift), the grid rebuilt at x1;
//   4. density and factor at x1, then the divergence solve: v1 corrected until drho/dt ~ 0.
// Each solve starts from half of the previous step's kappa sum (the warm start) and runs at
// least 2 (density) or 1 (divergence) iterations, until its mean residual is within its error
// bound. The host queues as many iterations as the solve took the step before, then reads their
// residuals in one wait (queued behind the last rate, so that its correction runs meanwhile);
// an iteration queued after one that converged does nothing (the kernels test the residual
// slot before it on the device), so the result is the bits of one read per iteration. The step
// ends, like leapfrog's, with the fields at the new positions, so the next step starts there.
//
// On several ranks (sph_ranks.h) each kernel computes the rank's own particles, and what a
// kernel reads of its neighbours comes from their owners first: the density after each density
// pass (the viscosity reads it; dfsph's force has no pressure term), the velocities before a
// solve's first rate, after every correction that another iteration follows and at the end of the
// step (the next step's viscosity reads them), each iteration's kappa before its correction. The
// residual is a sum of integers over the ranks, so every rank sees the one process's and stops at
// the same iteration. The kappa sums move with the particles at the rebuilds, the halos' included,
// which is all the warm starts read of them.
#include "engine/sph/sph_dfsph_scheme.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "engine/sph/sph_device_state.h"
#include "engine/sph/sph_field_evaluator.h"
#include "engine/sph/sph_kernel_calls.h"
#include "engine/sph/sph_ranks.h"

namespace masav {

// The neighbour count below which the divergence solve skips a particle.
SphDfsphScheme::SphDfsphScheme(const SphContext& c) : SphScheme(c) {
  // The divergence solve skips particles with fewer than 3/4 of a full lattice's neighbours
  // (splashes, thin sheets), whose density change rate says little about compression.
  const double reach = c_.layout.h / c_.layout.dx;
  const int r = int(std::ceil(reach));
  uint32_t lattice = 0;
  for (int i = -r; i <= r; ++i)
    for (int j = -r; j <= r; ++j)
      for (int k = -r; k <= r; ++k)
        if (double(i * i + j * j + k * k) < reach * reach) ++lattice;
  min_neighbors_ = uint32_t(std::ceil(0.75 * lattice));
}

// The largest residual sum (kDfsphResidualScale units over `movers` particles) whose mean,
// units / scale / movers computed in double, is at most `target` (> 0: the scene's error bounds
// are at least 1e-7): the test the host made on the mean, as one integer comparison the kernels
// can make too. Starts from the rounded product and steps to the exact boundary.
uint64_t dfsph_stop_units(double target, uint32_t movers) {
  const double scale = double(kDfsphResidualScale), count = double(std::max(movers, 1u));
  auto within = [&](uint64_t u) { return double(u) / scale / count <= target; };
  const double guess = std::floor(target * scale * count);
  const double cap = double(UINT64_MAX >> 1);
  uint64_t u = guess >= cap ? uint64_t(cap) : uint64_t(std::max(guess, 0.0));
  while (u > 0 && !within(u)) --u;
  while (u < (UINT64_MAX >> 1) && within(u + 1)) ++u;
  return u;
}

DfsphParams SphDfsphScheme::params(DfsphSolve kind, double dt) const {
  DfsphParams p;
  p.step = c_.fields.params();
  p.solve = kind;
  p.dt = dt;
  p.min_neighbors = min_neighbors_;
  return p;
}

void SphDfsphScheme::fields_at(const Buffer<Real4>& x) {
  const SphGridView view = sph_grid_view(c_.fields.grid());
  sph_density(c_.backend, c_.fields.params(),
              SphDensityIO{&x, view, &c_.device.density, &c_.device.pressure, &c_.device.stats,
                           c_.fields.neighbor_rows()});
  if (c_.ranks) c_.ranks->exchange_halos(c_.device.density);  // dfsph's force reads no pressure
  c_.fields.mark(SphStage::density);
  DfsphIO io;
  io.positions = &x;
  io.grid = view;
  io.factor = &c_.device.factor;
  io.stats = &c_.device.stats;
  io.neighbor_rows = c_.fields.neighbor_rows();
  dfsph_factor(c_.backend, params(DfsphSolve::density, 1.0), io);
  c_.fields.mark(SphStage::solve);
}

void SphDfsphScheme::solve(DfsphSolve kind, double dt, const Buffer<Real4>& x, Buffer<Real4>& v,
                           Buffer<Real>& kappa_sum) {
  const bool density = kind == DfsphSolve::density;
  const double target = density ? c_.scene.dfsph_density_error : c_.scene.dfsph_divergence_error;
  const uint32_t min_iterations = density ? 2 : 1;
  const uint32_t max_iterations = c_.scene.dfsph_max_iterations;
  const uint32_t movers = c_.layout.fluid + (c_.scene.obstacle.pinned ? 0u : c_.layout.obstacle);
  DfsphParams p = params(kind, dt);
  DfsphIO io;
  io.positions = &x;
  io.velocities = &v;
  io.density = &c_.device.density;
  io.factor = &c_.device.factor;
  io.grid = sph_grid_view(c_.fields.grid());
  io.kappa_sum = &kappa_sum;
  io.residual = &c_.device.residual;
  io.stats = &c_.device.stats;
  io.neighbor_rows = c_.fields.neighbor_rows();
  c_.backend.fill(c_.device.residual, 0u);
  if (kappa_warm_) {  // warm start: warm_scale of the last solve's kappa sum
    p.first = true;
    io.kappa = &kappa_sum;
    dfsph_correct(c_.backend, p, io);
  }
  // The halos' velocities: the density solve's come from the prediction v + dt a, computed for
  // the own particles only; a warm start changed the own ones.
  if (c_.ranks && (density || kappa_warm_)) c_.ranks->exchange_halos(v);
  io.kappa = &c_.device.kappa;
  const uint64_t stop_units = dfsph_stop_units(target, movers);
  uint32_t& expected = last_iterations_[density ? 1 : 0];
  uint32_t done = 0;
  double error = 0;
  bool converged = false;
  while (done < max_iterations && !converged) {
    // Iterations queued before the host reads a residual: as many as the last solve took (its
    // warm start makes the next one much alike; once those are done, one at a time), each from
    // the second on doing nothing if the one before converged (stop_slot), so the result is the
    // one of a read per iteration. On a GPU one more: an iteration that does nothing costs two
    // launches that return at once, a read a round trip of the host, while the GPU idles. On
    // several ranks the residual is summed over them on the host: one iteration per read.
    const uint32_t want = expected + (c_.backend.caps().device_type != "cpu" ? 1u : 0u);
    const uint32_t batch =
        c_.ranks || !queue_ ? 1u
                            : std::clamp(want > done ? want - done : 1u, 1u, max_iterations - done);
    const uint32_t first_read = std::max(done, min_iterations - 1);
    uint64_t residual_read = 0;
    try {
      for (uint32_t b = 0; b < batch; ++b) {
        const uint32_t it = done + b;
        p.slot = it;
        p.first = it == 0;
        p.stop_slot = b > 0 && it >= min_iterations ? it - 1 : kDfsphNoStop;
        p.stop_units = stop_units;
        dfsph_rate(c_.backend, p, io);
        // The batch's residual slots, read behind its last rate: the correction runs meanwhile
        // (and on several ranks the kappa exchange's wait covers it).
        if (b + 1 == batch && it >= first_read)
          residual_read = c_.backend.read_async(c_.device.residual.impl(),
                                                2 * sizeof(uint32_t) * (it + 1 - first_read),
                                                2 * size_t(first_read) * sizeof(uint32_t));
        if (c_.ranks) c_.ranks->exchange_halos(c_.device.kappa);
        p.first = false;
        dfsph_correct(c_.backend, p, io);
      }
    } catch (...) {
      c_.backend.discard_read(residual_read);
      throw;
    }
    const uint32_t end = done + batch;
    done = end;
    if (residual_read) {
      const std::vector<uint32_t> words = c_.backend.take_u32s(residual_read);
      ++residual_reads_;
      for (uint32_t it = first_read; it < end; ++it) {
        const size_t w = 2 * size_t(it - first_read);
        uint64_t units = uint64_t(words[w + 1]) << 32 | words[w];
        if (c_.ranks) units = c_.ranks->sum(units);
        error = double(units) / double(kDfsphResidualScale) / double(std::max(movers, 1u));
        if (units <= stop_units) {  // the later iterations of the batch did nothing
          converged = true;
          done = it + 1;
          break;
        }
      }
    }
    if (c_.ranks && !converged && done < max_iterations) c_.ranks->exchange_halos(v);
  }
  expected = done;
  // The divergence solve's velocities are the step's: the next step's viscosity reads the
  // halos' (the density solve's move with the particles at the rebuild instead).
  if (c_.ranks && !density) c_.ranks->exchange_halos(v);
  c_.fields.mark(SphStage::solve);
  (density ? solve_stats_.density_iterations : solve_stats_.divergence_iterations) += done;
  (density ? solve_stats_.last_density_error : solve_stats_.last_divergence_error) = error;
  if (!converged) ++solve_stats_.unconverged;
}

void SphDfsphScheme::record(double dt) {
  SphDeviceState& d = c_.device;
  SphFieldEvaluator& f = c_.fields;
  if (!c_.progress.accel_valid) {  // density and factor at pos (a new start, or after a roll back)
    f.sort_state();
    fields_at(d.pos);
    c_.backend.fill(d.kappa_density, 0u);
    c_.backend.fill(d.kappa_divergence, 0u);
    kappa_warm_ = false;
    c_.progress.accel_valid = true;
  }
  const SphGridView view = sph_grid_view(f.grid());
  sph_forces(c_.backend, f.params(),
             SphForcesIO{&d.pos, &d.vel, &d.density, &d.pressure, view, &d.accel, &d.stats,
                         f.neighbor_rows()});
  f.mark(SphStage::forces);
  f.integrate(SphStageOp::accelerate, dt, d.pos, d.vel, nullptr, nullptr, d.vs, nullptr, nullptr);
  solve(DfsphSolve::density, dt, d.pos, d.vs, d.kappa_density);
  f.integrate(SphStageOp::drift, dt, d.pos, d.vs, nullptr, &d.xs, d.vs, nullptr, nullptr);
  // The kappa sums move with the particles (the warm starts), and so do the forces, whose w
  // counts the neighbours that download() reports by particle.
  const SphCarried carried[] = {{d.kappa_density, d.kappa_density_t},
                                {d.kappa_divergence, d.kappa_divergence_t},
                                {d.accel, d.tc}};
  f.rebuild_drifted(carried);
  std::swap(d.accel, d.tc);
  f.mark(SphStage::grid);
  c_.progress.accel_valid = false;  // density and factor now belong to the new positions
  fields_at(d.ta);
  solve(DfsphSolve::divergence, dt, d.ta, d.tb, d.kappa_divergence_t);
  ++solve_stats_.steps;
}

void SphDfsphScheme::commit() {
  SphDeviceState& d = c_.device;
  std::swap(d.kappa_density, d.kappa_density_t);
  std::swap(d.kappa_divergence, d.kappa_divergence_t);
  kappa_warm_ = true;
  commit_rebuilt();
}

void SphDfsphScheme::restore_fields() {
  // A dfsph step starts from the grid, density, factor and neighbour rows at pos, which the
  // step before left: rebuilt here (the kappa sums move with the particles; on several ranks
  // this rebuild brings the halos). The positions are in the cell order of that step's
  // rebuild, which the stable counting sort keeps, so the sums run in the same order.
  if (!c_.progress.accel_valid) return;
  c_.fields.sort_state();
  fields_at(c_.device.pos);
}

void SphDfsphScheme::restore(const SphSolveStats& stats, bool kappa_warm) {
  solve_stats_ = stats;
  kappa_warm_ = kappa_warm;
}

}  // namespace masav
