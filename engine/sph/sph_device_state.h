#pragma once
// The SPH simulation's per-particle device arrays: the committed state in the order of the last
// grid rebuild, the integrators' scratch, the masks and neighbour state the kernels may keep,
// dfsph's solve arrays and run()'s block checkpoints. Decides what fits the device's memory
// (sph_device_state.cpp) and, on several ranks, sizes the arrays for a rank's share and its
// halos rather than for every particle (so that memory per rank falls as ranks are added),
// growing them when a rank takes more.
//
// The buffers are public fields, like HashGrid's: every part of the simulation reads and swaps
// them, and a swap (the step's results becoming the state) is all a commit is.
#include <array>
#include <cstdint>

#include "engine/grid/hash_grid.h"
#include "engine/kernels/backend.h"
#include "engine/sph/sph_params.h"

namespace masav {

// One of run()'s device-side copies of the state at a block's start (sph_block_scheduler.h).
struct SphBlockCheckpoint {
  Buffer<Real4> pos, vel, accel;
  Buffer<uint32_t> ids;
  Buffer<uint32_t> stats;  // a later part's block stats so far (the first part's start from 0)
};

class SphDeviceState {
 public:
  // `ranks`: how many share the simulation; `particles`: all of theirs together.
  SphDeviceState(Backend& backend, const SphScene& scene, uint32_t particles, int ranks);

  // The particles a rank's buffers start with room for, and the refusals, before anything is
  // allocated, of a count the device cannot hold: one buffer of positions, then the memory
  // budget.
  static uint32_t initial_capacity(uint64_t particles, int ranks);
  static void check_capacity(const Backend& b, const SphScene& s, int ranks);
  static void check_buffer_size(const Backend& b, uint64_t particles, int ranks);

  // Every buffer, at the initial capacity: the stats words, then the per-particle arrays and
  // whichever masks, neighbour state and checkpoints fit.
  void allocate();
  // On several ranks: room for `local` particles in every per-particle buffer and in `grid`'s
  // per-point tables, the contents kept.
  void reserve(uint32_t local, HashGrid& grid);

  // The particles each per-particle buffer holds (SphSimulation::capacity()).
  uint32_t capacity() const { return capacity_; }
  uint64_t capacity_growths() const { return capacity_growths_; }

  // Committed state (pos, vel, ids, accel, density, pressure) and scratch: the stage arrays
  // (xs, vs), RK4's sums, the rebuild's sorted arrays (ta, tb, tc, ids_t).
  Buffer<Real4> pos, vel, xs, vs, sum_x, sum_v, ta, tb, tc, accel;
  Buffer<uint32_t> ids, ids_t, stats;
  // sph_density's neighbour row masks for sph_forces at the same positions (every evaluation
  // runs both); empty where they are not kept (keeps_neighbor_rows in the .cpp).
  Buffer<uint32_t> neighbor_rows;
  // RK4: sph_density's reach masks of the step's first evaluation (within the grid's cell size,
  // h + skin rounded up), which its other three walk (SphReach); empty where not kept
  // (keeps_reach_rows in the .cpp).
  Buffer<uint32_t> reach_rows;
  // sph_density's neighbour state (kSphStateStride) for sph_forces at the same positions and
  // velocities; empty where not kept (neighbor_state_fits in the .cpp).
  Buffer<Real4> neighbor_state;
  Buffer<Real> density, pressure;
  // dfsph: the factor at pos (or the step's new positions), one iteration's kappa, each solve's
  // kappa sum in pos's order (warm starts) and in the new order, the residual slots.
  Buffer<Real> factor, kappa, kappa_density, kappa_divergence, kappa_density_t, kappa_divergence_t;
  Buffer<uint32_t> residual;
  // The states at the start of run()'s pending block and of the one after it; empty where they
  // do not fit (the second: where it does not, or on several ranks).
  std::array<SphBlockCheckpoint, 2> checkpoints;

 private:
  void allocate_dfsph();

  Backend& backend_;
  const SphScene& scene_;
  uint32_t n_;
  bool ranks_;  // several ranks share the simulation
  uint32_t capacity_ = 0;
  uint64_t capacity_growths_ = 0;
};

}  // namespace masav
