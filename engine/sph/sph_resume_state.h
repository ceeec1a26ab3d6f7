#pragma once
// What a checkpoint keeps of an SPH simulation (sph_checkpoint.h): SphSimulation's
// export_resume_state gathers it from the parts (sph_simulation_resume.cpp), and
// restore_resume_state hands it back to them.
#include <cstdint>
#include <vector>

#include "engine/sph/sph_state.h"
#include "engine/sph/sph_watchdog.h"

namespace masav {

// Everything the simulation's next steps depend on besides its scene: the committed device
// arrays in the order of the last grid rebuild (the next step's neighbour sums run in that
// order), the host's step control and the watchdog's baseline. A simulation built from the same
// scene and given this continues the trajectory the exporting one would have taken, bit for bit
// on one backend.
struct SphResumeState {
  std::vector<Vec4d> positions, velocities, accel;  // accel: leapfrog's carried force, w = count
  std::vector<uint32_t> ids;
  std::vector<double> density, pressure;                // at positions, when fields_current
  std::vector<double> kappa_density, kappa_divergence;  // dfsph's warm starts; empty otherwise
  double time = 0, last_dt = 0, adaptive_dt = 0;
  uint64_t steps = 0, substeps = 0, retries = 0, block_replays = 0;
  SphStepStats stats;      // the last read: the next dt's CFL limit (step())
  SphStepStats lag_stats;  // the read before it: the next block's CFL limit (run())
  SphSolveStats solve_stats;
  bool accel_valid = false, fields_current = false, kappa_warm = false;
  uint32_t block_steps = 8;
  // A block that a call to run() left open (sph_block_scheduler.h): its dt limit and the stats
  // words accumulated on the device so far (kSphStatWords; empty when none is open).
  double block_limit = 0;
  std::vector<uint32_t> block_stats;
  SphWatchdog watchdog;
  uint64_t next_energy_check = 0;
  // The watchdog's last state that passed its energy check, by particle id.
  std::vector<Vec4d> good_positions, good_velocities;
  double good_time = 0, good_last_dt = 0;
  uint64_t good_steps = 0, good_substeps = 0;
  SphStepStats good_stats;
};

}  // namespace masav
