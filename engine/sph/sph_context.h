#pragma once
// What the parts of an SPH simulation (sph_simulation.h) share: the host's step state, which a
// rolled-back block or a failed energy check restores, and SphContext, the references every
// part is built with (the backend, the scene and its particles, the ranks, the committed device
// arrays, the field evaluator and that host state). The facade owns all of them.
#include <cstdint>

#include "engine/kernels/backend.h"
#include "engine/sph/sph_params.h"
#include "engine/sph/sph_particles.h"
#include "engine/sph/sph_state.h"

namespace masav {

class SphDeviceState;
class SphFieldEvaluator;
class SphRanks;

// The host's side of the committed state: time and step control, the stats its next dt comes
// from, what the device arrays hold and run()'s open block. A block's rollback restores all of
// it (SphBlockScheduler); the counters that only grow (retries, replays) live elsewhere.
struct SphProgress {
  double time = 0, last_dt = 0, adaptive_dt = 0;
  uint64_t steps = 0, substeps = 0;
  SphStepStats stats;           // the last read: the next step's dt limit
  SphStepStats lag_stats;       // the stats before stats' block (sph_block_scheduler.h)
  bool accel_valid = false;     // leapfrog: accel holds a(pos) in pos's order; dfsph: fields at pos
  bool fields_current = false;  // density, pressure, accel belong to pos (pos's order)
  // The block of the fixed schedule that run() left open, and its dt limit.
  bool block_open = false;
  double block_limit = 0;
  uint64_t next_energy_check = 0;  // the step of the watchdog's next energy check
};

struct SphContext {
  Backend& backend;
  const SphScene& scene;
  const SphParticles& layout;  // spacing, h, mass, counts
  SphRanks* ranks;             // the decomposition on several ranks; null in one process
  SphDeviceState& device;
  SphFieldEvaluator& fields;
  SphProgress& progress;

  uint32_t n() const { return layout.total(); }  // all ranks' particles together
  bool dfsph() const { return scene.model == SphPressureModel::dfsph; }
  // The step ends with a rebuild at its new positions (leapfrog, dfsph): its result is in the
  // rebuild's arrays (ta, tb, ids_t) and its force pass belongs to them.
  bool ends_rebuilt() const { return scene.integrator == SphIntegrator::leapfrog || dfsph(); }
};

}  // namespace masav
