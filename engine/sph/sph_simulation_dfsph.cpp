// SphSimulation's step for the dfsph pressure model (divergence-free SPH, Bender & Koschier;
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
#include <algorithm>
#include <cmath>

#include "engine/sph/sph_kernel_calls.h"
#include "engine/sph/sph_simulation.h"

namespace masav {

// The solves' buffers, and the neighbour count below which the divergence solve skips a particle.
void SphSimulation::allocate_dfsph() {
  auto real = [&](const char* label) { return backend_.create<Real>(capacity_, label); };
  factor_ = real("dfsph factor");
  kappa_ = real("dfsph kappa");
  kappa_density_ = real("dfsph density kappa sums");
  kappa_divergence_ = real("dfsph divergence kappa sums");
  kappa_density_t_ = real("dfsph sorted density kappa sums");
  kappa_divergence_t_ = real("dfsph sorted divergence kappa sums");
  residual_ = backend_.create<uint32_t>(kDfsphResidualWords, "dfsph residuals");
  // The divergence solve skips particles with fewer than 3/4 of a full lattice's neighbours
  // (splashes, thin sheets), whose density change rate says little about compression.
  const double reach = layout_.h / layout_.dx;
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

DfsphParams SphSimulation::dfsph_params(DfsphSolve solve, double dt) const {
  DfsphParams p;
  p.step = step_params_;
  p.solve = solve;
  p.dt = dt;
  p.min_neighbors = min_neighbors_;
  return p;
}

void SphSimulation::dfsph_fields(const Buffer<Real4>& x) {
  const SphGridView view = sph_grid_view(grid_);
  sph_density(backend_, step_params_,
              SphDensityIO{&x, view, &density_, &pressure_, &stats_buf_, neighbor_rows()});
  if (ranks_) ranks_->exchange_halos(density_);  // dfsph's force reads no pressure
  mark(SphStage::density);
  DfsphIO io;
  io.positions = &x;
  io.grid = view;
  io.factor = &factor_;
  io.stats = &stats_buf_;
  io.neighbor_rows = neighbor_rows();
  dfsph_factor(backend_, dfsph_params(DfsphSolve::density, 1.0), io);
  mark(SphStage::solve);
}

void SphSimulation::dfsph_solve(DfsphSolve solve, double dt, const Buffer<Real4>& x,
                                Buffer<Real4>& v, Buffer<Real>& kappa_sum) {
  const bool density = solve == DfsphSolve::density;
  const double target = density ? scene_.dfsph_density_error : scene_.dfsph_divergence_error;
  const uint32_t min_iterations = density ? 2 : 1;
  const uint32_t max_iterations = scene_.dfsph_max_iterations;
  const uint32_t movers = layout_.fluid + (scene_.obstacle.pinned ? 0u : layout_.obstacle);
  DfsphParams p = dfsph_params(solve, dt);
  DfsphIO io;
  io.positions = &x;
  io.velocities = &v;
  io.density = &density_;
  io.factor = &factor_;
  io.grid = sph_grid_view(grid_);
  io.kappa_sum = &kappa_sum;
  io.residual = &residual_;
  io.stats = &stats_buf_;
  io.neighbor_rows = neighbor_rows();
  backend_.fill(residual_, 0u);
  if (kappa_warm_) {  // warm start: warm_scale of the last solve's kappa sum
    p.first = true;
    io.kappa = &kappa_sum;
    dfsph_correct(backend_, p, io);
  }
  // The halos' velocities: the density solve's come from the prediction v + dt a, computed for
  // the own particles only; a warm start changed the own ones.
  if (ranks_ && (density || kappa_warm_)) ranks_->exchange_halos(v);
  io.kappa = &kappa_;
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
    const uint32_t want = expected + (backend_.caps().device_type != "cpu" ? 1u : 0u);
    const uint32_t batch = ranks_ || !dfsph_queue_ ? 1u
                                                   : std::clamp(want > done ? want - done : 1u, 1u,
                                                                max_iterations - done);
    const uint32_t first_read = std::max(done, min_iterations - 1);
    uint64_t residual_read = 0;
    try {
      for (uint32_t b = 0; b < batch; ++b) {
        const uint32_t it = done + b;
        p.slot = it;
        p.first = it == 0;
        p.stop_slot = b > 0 && it >= min_iterations ? it - 1 : kDfsphNoStop;
        p.stop_units = stop_units;
        dfsph_rate(backend_, p, io);
        // The batch's residual slots, read behind its last rate: the correction runs meanwhile
        // (and on several ranks the kappa exchange's wait covers it).
        if (b + 1 == batch && it >= first_read)
          residual_read =
              backend_.read_async(residual_.impl(), 2 * sizeof(uint32_t) * (it + 1 - first_read),
                                  2 * size_t(first_read) * sizeof(uint32_t));
        if (ranks_) ranks_->exchange_halos(kappa_);
        p.first = false;
        dfsph_correct(backend_, p, io);
      }
    } catch (...) {
      backend_.discard_read(residual_read);
      throw;
    }
    const uint32_t end = done + batch;
    done = end;
    if (residual_read) {
      const std::vector<uint32_t> words = backend_.take_u32s(residual_read);
      ++dfsph_residual_reads_;
      for (uint32_t it = first_read; it < end; ++it) {
        const size_t w = 2 * size_t(it - first_read);
        uint64_t units = uint64_t(words[w + 1]) << 32 | words[w];
        if (ranks_) units = ranks_->sum(units);
        error = double(units) / double(kDfsphResidualScale) / double(std::max(movers, 1u));
        if (units <= stop_units) {  // the later iterations of the batch did nothing
          converged = true;
          done = it + 1;
          break;
        }
      }
    }
    if (ranks_ && !converged && done < max_iterations) ranks_->exchange_halos(v);
  }
  expected = done;
  // The divergence solve's velocities are the step's: the next step's viscosity reads the
  // halos' (the density solve's move with the particles at the rebuild instead).
  if (ranks_ && !density) ranks_->exchange_halos(v);
  mark(SphStage::solve);
  (density ? solve_stats_.density_iterations : solve_stats_.divergence_iterations) += done;
  (density ? solve_stats_.last_density_error : solve_stats_.last_divergence_error) = error;
  if (!converged) ++solve_stats_.unconverged;
}

void SphSimulation::step_dfsph(double dt) {
  if (!accel_valid_) {  // density and factor at pos_ (a new start, or after a roll back)
    sort_state();
    dfsph_fields(pos_);
    backend_.fill(kappa_density_, 0u);
    backend_.fill(kappa_divergence_, 0u);
    kappa_warm_ = false;
    accel_valid_ = true;
  }
  const SphGridView view = sph_grid_view(grid_);
  sph_forces(backend_, step_params_,
             SphForcesIO{&pos_, &vel_, &density_, &pressure_, view, &accel_, &stats_buf_,
                         neighbor_rows()});
  mark(SphStage::forces);
  integrate(SphStageOp::accelerate, dt, pos_, vel_, nullptr, nullptr, vs_, nullptr, nullptr);
  dfsph_solve(DfsphSolve::density, dt, pos_, vs_, kappa_density_);
  integrate(SphStageOp::drift, dt, pos_, vs_, nullptr, &xs_, vs_, nullptr, nullptr);
  // The kappa sums move with the particles (the warm starts), and so do the forces, whose w
  // counts the neighbours that download() reports by particle.
  const SphCarried carried[] = {
      {kappa_density_, kappa_density_t_}, {kappa_divergence_, kappa_divergence_t_}, {accel_, tc_}};
  if (ranks_) {
    ranks_->redistribute(xs_, vs_, ids_, carried, ta_, tb_, ids_t_);
    use_rank_layout(ta_);
  } else {
    rebuild_moving(xs_, ta_, vs_, tb_, ids_, ids_t_);
    for (const SphCarried& c : carried) reorder(backend_, grid_, c.from(), c.to());
  }
  std::swap(accel_, tc_);
  mark(SphStage::grid);
  accel_valid_ = false;  // density_ and factor_ now belong to the new positions
  dfsph_fields(ta_);
  dfsph_solve(DfsphSolve::divergence, dt, ta_, tb_, kappa_divergence_t_);
  ++solve_stats_.steps;
}

}  // namespace masav
