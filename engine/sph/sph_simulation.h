#pragma once
// The SPH simulation: one scene's particles on one backend (or shared among ranks), stepped by
// the scene's integrator with a guarded dt, its state read back for diagnostics, export and
// checkpoints. Independent of the command line, so the renderer can drive it.
//
// A facade over its parts, each in its own file:
//  - SphDeviceState (sph_device_state.h): the committed device arrays, scratch, masks and
//    checkpoints, what fits the device's memory, a rank's growth;
//  - SphFieldEvaluator (sph_field_evaluator.h): the hash grid and its rebuilds, density, forces
//    and integrate calls, the stats words, the stage timing marks;
//  - SphScheme (sph_scheme.h): one integrator per scheme (Euler, leapfrog, RK4, dfsph's);
//  - SphStepControl (sph_step_control.h): dt, the CFL guard, the judge of a step's stats;
//  - SphBlockScheduler (sph_block_scheduler.h): run()'s blocks with asynchronous stats,
//    checkpoints and replays;
//  - SphEnergyWatch (sph_energy_watch.h): the watchdog's energy check (sph_watchdog.h);
//  - SphStateReader (sph_state_reads.h): the state reads;
//  - SphRanks (sph_ranks.h): the rank domain. Given a communicator of more than one rank, each
//    rank computes the particles of its cells, the rebuilds move particles between ranks and
//    bring halos, the stats are reduced over the ranks, and the trajectory is the one process's,
//    bit for bit, for every pressure model. download() gathers the whole state on every rank,
//    and a checkpoint (export_resume_state) holds the one-process arrays, so a run restores on
//    any number of ranks.
#include <array>
#include <cstdint>
#include <limits>
#include <memory>
#include <vector>

#include "engine/kernels/backend.h"
#include "engine/sph/sph_block_scheduler.h"
#include "engine/sph/sph_comm.h"
#include "engine/sph/sph_context.h"
#include "engine/sph/sph_device_state.h"
#include "engine/sph/sph_energy_watch.h"
#include "engine/sph/sph_field_evaluator.h"
#include "engine/sph/sph_ranks.h"
#include "engine/sph/sph_resume_state.h"
#include "engine/sph/sph_scheme.h"
#include "engine/sph/sph_state.h"
#include "engine/sph/sph_state_reads.h"
#include "engine/sph/sph_step_control.h"

namespace masav {

class SphDfsphScheme;

class SphSimulation {
 public:
  // `comm`: the ranks sharing the simulation (see the header); null or one rank: this process
  // alone.
  SphSimulation(Backend& backend, const SphScene& scene, SphComm* comm = nullptr);

  // Advances the simulation by one step: dt (fixed, possibly split into sub-steps by the CFL
  // guard) or the adaptive dt. Throws masav::Error (state left at the last good step).
  void step();
  // Up to `steps` steps, stopping early once time() reaches t_end; in blocks
  // (sph_block_scheduler.h). Returns the steps taken.
  uint64_t run(uint64_t steps, double t_end = std::numeric_limits<double>::infinity());
  // Steps per stats read in run(): 1 to kMaxBlockSteps (1 when no checkpoint fits).
  static constexpr uint32_t kMaxBlockSteps = SphBlockScheduler::kMaxBlockSteps;
  void set_block_steps(uint32_t k) { blocks_.set_block_steps(k); }
  uint32_t block_steps() const { return blocks_.block_steps(); }
  uint64_t block_replays() const { return blocks_.block_replays(); }  // blocks replayed
  // RK4: whether its later evaluations walk the first one's reach masks (SphReach).
  bool keeps_reach_masks() const { return device_.reach_rows.valid(); }
  // From now on every RK4 evaluation walks the inflated cells, as where the masks do not fit:
  // the tests' way to compare the two walks.
  void drop_reach_masks() { device_.reach_rows = {}; }
  // Whether sph_forces reads sph_density's neighbour state (kSphStateStride): where the
  // backend's SphTuning::neighbor_state allows and it fits.
  bool keeps_neighbor_state() const { return device_.neighbor_state.valid(); }

  double time() const { return progress_.time; }
  uint64_t steps() const { return progress_.steps; }
  uint64_t substeps() const { return progress_.substeps; }  // integrator steps actually taken
  uint64_t retries() const { return control_.retries(); }   // steps the guard rejected, retried
  double last_dt() const { return progress_.last_dt; }
  // The limit the CFL conditions give for the current state (s).
  double dt_limit() const { return control_.dt_limit(); }

  const SphScene& scene() const { return scene_; }
  const SphParticles& layout() const { return layout_; }       // spacing, h, mass, counts
  uint32_t particle_count() const { return layout_.total(); }  // all ranks' together
  // The particles this rank's buffers hold: all of them in one process; on several ranks its
  // share with room for halos, grown (never shrunk) when it takes more.
  uint32_t capacity() const { return device_.capacity(); }
  uint64_t capacity_growths() const { return device_.capacity_growths(); }
  // Whether the last error came from the simulation's own checks (the CFL guard, the watchdog,
  // a non-finite state, neighbour overflow), which decide on values reduced over the ranks: then
  // every rank raised it at the same step, and they can still write the state together.
  bool failed_together() const { return control_.failed_together(); }
  // The decomposition when the simulation runs on several ranks; null otherwise.
  const SphRanks* ranks() const { return ranks_.get(); }
  SphRanks* ranks() { return ranks_.get(); }
  SphStepParams step_params() const { return fields_.params(); }
  const SphStepStats& last_stats() const { return progress_.stats; }
  const SphSolveStats& solve_stats() const;  // dfsph only
  // dfsph: the residual reads (host waits) of the solves so far, and whether a solve queues
  // several iterations per read (on by default; off: one per iteration, the same bits).
  uint64_t dfsph_residual_reads() const;
  void set_dfsph_queued_iterations(bool on);
  Backend& backend() { return backend_; }

  // Current state, in particle-id order, with density and pressure at these positions (on
  // several ranks: every rank's particles, on every rank).
  SphState download() { return reads_.download(); }
  // This rank's own particles (every particle in one process), in the order of the last grid
  // rebuild, with their ids: what a rank writes as its piece of a snapshot.
  SphState download_own(std::vector<uint32_t>& ids) { return reads_.download_own(ids); }
  // The committed state on the backend, for a renderer to bind without a copy: in the order of
  // the last grid rebuild (not particle-id order); positions' w = inverse mass scale. density()
  // and pressure() are index-aligned with positions() and belong to the last force pass (at
  // most one step old) -- until download() evaluates at a re-sorted scratch copy.
  const Buffer<Real4>& positions() const { return device_.pos; }
  const Buffer<Real4>& velocities() const { return device_.vel; }
  const Buffer<Real>& density() const { return device_.density; }
  const Buffer<Real>& pressure() const { return device_.pressure; }
  // The particle id of each element of the four above (the order they are in).
  const Buffer<uint32_t>& ids() const { return device_.ids; }
  // Replaces the velocities (indexed by particle id), e.g. to start from a velocity field.
  void set_velocities(const std::vector<Vec4d>& by_id);

  // The state a checkpoint keeps (sph_simulation_resume.cpp); restore_resume_state takes one
  // exported by a simulation of the same scene, every field checked first (sph_resume_checks.h:
  // throws masav::Error naming the field, its value and the allowed range).
  SphResumeState export_resume_state();
  void restore_resume_state(const SphResumeState& r);

  // Device time per stage, summed since the last reset (recorded when profiling is on).
  void set_profiling(bool on) { fields_.set_profiling(on); }
  std::array<double, size_t(SphStage::count)> stage_ms() const { return fields_.stage_ms(); }
  void reset_stage_ms() { fields_.stage_ms().fill(0.0); }

 private:
  // The parts, in the order they are built (each one's references to those before it).
  Backend& backend_;
  SphScene scene_;
  SphParticles layout_;
  SphGridShape grid_shape_;
  std::unique_ptr<SphRanks> ranks_;  // several ranks only
  SphDeviceState device_;
  SphFieldEvaluator fields_;
  SphProgress progress_;
  SphContext context_;
  std::unique_ptr<SphScheme> scheme_;
  SphDfsphScheme* dfsph_ = nullptr;  // scheme_, for the dfsph model
  SphStateReader reads_;
  SphEnergyWatch watch_;
  SphStepControl control_;
  SphBlockScheduler blocks_;
};

}  // namespace masav
