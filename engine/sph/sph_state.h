#pragma once
// What an SPH simulation hands to its callers on the host: a state by particle id, the stats of
// a step, the stages its device time is split into and dfsph's solve counters. Separate from
// sph_simulation.h so that the parts of the simulation and its readers (diagnostics, export,
// the watchdog) share them without the facade.
#include <cstdint>
#include <vector>

#include "engine/core/types.h"

namespace masav {

// Particle state on the host, in particle-id order (ids are the initial order: fluid first).
struct SphState {
  std::vector<Vec4d> positions;   // m; w = inverse mass scale
  std::vector<Vec4d> velocities;  // m/s
  std::vector<double> density;    // kg/m^3, at these positions
  std::vector<double> pressure;   // Pa
  std::vector<double> neighbors;  // within h, itself included
};

// A state of n particles, every array sized (to be filled by id).
SphState sized_state(size_t n);

// The maxima of a step (or of a block of steps) that the device accumulates in its stats words
// (kSphStatWords) and the host reads back.
struct SphStepStats {
  double max_speed = 0, max_accel = 0, max_drift = 0;  // m/s, m/s^2, m
  double max_density = 0;                              // kg/m^3
  uint32_t max_candidates = 0, max_neighbors = 0, outside = 0;
};

enum class SphStage : uint8_t { grid, density, forces, integrate, solve, count };
const char* to_string(SphStage s);

// The dfsph model's pressure solves since the start (engine/kernels/dfsph_kernels.h).
struct SphSolveStats {
  uint64_t steps = 0;               // steps that ran both solves
  uint64_t density_iterations = 0;  // summed over the steps
  uint64_t divergence_iterations = 0;
  uint64_t unconverged = 0;       // solves that stopped at dfsph_max_iterations
  double last_density_error = 0;  // the last density solve's final mean residual
  double last_divergence_error = 0;
};

}  // namespace masav
