#pragma once
// The dfsph pressure model's step (divergence-free SPH, Bender & Koschier; formulas in
// engine/kernels/dfsph_kernels.h): viscosity and gravity, the density solve, the drift with its
// rebuild, the divergence solve (sph_dfsph_scheme.cpp says how). It keeps the solves' warm
// starts (the kappa sums, in SphDeviceState), how many iterations each took last and their
// counters. dfsph steps one at a time (its solves read residuals): run() records no blocks.
#include <cstdint>

#include "engine/sph/sph_scheme.h"
#include "engine/sph/sph_state.h"

namespace masav {

// The largest residual sum of a DFSPH solve (kDfsphResidualScale units over `movers` particles)
// whose mean is at most `target`: the convergence test as the integer comparison the kernels
// make (DfsphParams::stop_units).
uint64_t dfsph_stop_units(double target, uint32_t movers);

class SphDfsphScheme final : public SphScheme {
 public:
  explicit SphDfsphScheme(const SphContext& c);

  void record(double dt) override;
  void commit() override;

  // Density and factor at x (the grid sorted at x).
  void fields_at(const Buffer<Real4>& x);
  // After a checkpoint's restore: the grid, density, factor and neighbour rows at pos that the
  // step before left, where the next step starts from them (accel_valid).
  void restore_fields();

  const SphSolveStats& solve_stats() const { return solve_stats_; }
  bool kappa_warm() const { return kappa_warm_; }
  void restore(const SphSolveStats& stats, bool kappa_warm);
  // The residual reads (host waits) of the solves so far, and whether a solve queues several
  // iterations per read (on by default; off: one per iteration, the same bits).
  uint64_t residual_reads() const { return residual_reads_; }
  void set_queued_iterations(bool on) { queue_ = on; }

 private:
  DfsphParams params(DfsphSolve kind, double dt) const;
  // One solve on velocities v with its kappa sum.
  void solve(DfsphSolve kind, double dt, const Buffer<Real4>& x, Buffer<Real4>& v,
             Buffer<Real>& kappa_sum);

  bool kappa_warm_ = false;  // the kappa sums hold a previous step's (in pos's order)
  uint32_t min_neighbors_ = 0;
  // Iterations each solve (divergence, density) took last: how many the next queues before it
  // reads a residual.
  uint32_t last_iterations_[2] = {0, 0};
  bool queue_ = true;
  uint64_t residual_reads_ = 0;
  SphSolveStats solve_stats_;
};

}  // namespace masav
