#pragma once
// The SPH simulation driver: owns the particle buffers on one backend, rebuilds the hash grid
// (the foundation's sort on only the cell bits in use), calls the SPH kernels in the order each
// integrator needs, chooses dt (fixed or CFL-adaptive) and guards it, and reads back state for
// diagnostics and export. Independent of the command line, so the renderer can drive it.
//
// Grid rebuilds. Every step starts (Euler, RK4) or ends its drift (leapfrog) with a rebuild:
// the counting sort by cell of the current positions, whose rank pass also moves positions,
// velocities and particle ids into cell order (grid_rank_and_move), so the neighbour loops read
// neighbours from contiguous memory.
//  - Euler / symplectic Euler: one force pass per step at the step-start positions.
//  - Leapfrog (kick-drift-kick): the grid is rebuilt after the drift; the force pass there
//    serves this step's second kick and the next step's first (one pass per step).
//  - RK4: ONE rebuild per step, not per stage. The four stages evaluate forces at positions up
//    to dt |v| away from the step start; the grid's cells are h (1 + rk4_skin) wide, so a pair
//    within h at a stage was within h + skin h of each other at the rebuild and lies in the 27
//    cells walked (each particle drifts at most skin h / 2, which sph_integrate measures every
//    stage; a step that drifts further is rejected and retried with a smaller dt). Rebuilding
//    per stage would cost three more sorts and re-gathers of six arrays per step. The first
//    evaluation walks the 27 inflated cells and records which candidates lie within h + skin
//    (the reach masks, SphReach); the other three test only those, not the 27 cells' 27 / (4/3 pi)
//    ~ 6.4 times as many (where the masks do not fit, every evaluation walks the cells).
//
// CFL guard. dt is limited by C_v h / (c + v_max), C_f sqrt(h / a_max) and C_nu h^2 / nu (and
// the skin for RK4). Adaptive mode takes the smallest (growing at most 25% per step). A fixed dt
// over the limit is split into equal sub-steps (guard `reduce`) or stops with advice (`stop`).
// After every step the new velocities are checked: a step whose Courant number exceeded twice
// the limit, whose RK4 drift exceeded the skin, or that produced a NaN/Inf is rolled back and
// retried with half the dt; below dt_min the run stops with advice. A NaN that persists names the
// step and the particle. The last good state stays available (download()) after any error.
//
// Blocks. step() reads the stats back after every step: one host wait per step, which on a GPU
// leaves the device idle while the host decides. run() instead records up to block_steps()
// steps (default 8) with the stats accumulated on the device (maxima over the block) and reads
// them asynchronously (DeviceApi::read_async): block b is submitted, then the host takes block
// b-1's stats, which the device finished while b was queued, and records block b+1 while b
// runs. So a block's dt cannot come from the block just before it: block b's dt limit is the
// one of block b-2's stats (the block before the last, whatever run()'s calls or a replay left
// settled), its adaptive dt growing at most 25% per step from there. A block whose stats the
// guard would not accept (NaN/Inf, an overflow, an RK4 drift past the skin, a Courant number
// over twice the limit at the block's largest dt) is rolled back to a device-side checkpoint
// taken at its start (copies of positions, velocities, ids and, for leapfrog, accelerations;
// two of them, the pending block's and the one after it, which the rollback drops) and replayed
// with step(), so the guard retries or stops at the very step it would have without blocks:
// detection is bounded by two blocks, the message names the step. Where the second checkpoint
// does not fit the device's memory, and on several ranks (whose rebuilds exchange particles
// through the host every step), each block's stats are taken as soon as it is submitted; where
// none fits, run() steps one at a time. run() returns with every block it recorded settled.
//
// Blocks fall on fixed steps, multiples of block_steps() from step 0, however the calls to run()
// split them (a CSV row, a snapshot or a checkpoint every few steps): a block's later parts keep
// its first part's dt limit, and the device keeps accumulating its stats, so the dt of every
// step, and with it the trajectory, is the same whatever is written on the way. Only a replay
// (a block the guard rejects) ends a block where it stands.
//
// The stability watchdog (sph_watchdog.h) stops a blown-up run whatever the guard's mode.
//
// Ranks. Given a communicator of more than one rank, the simulation is shared among them
// (sph_ranks.h): each rank computes the particles of its cells, the rebuilds move particles
// between ranks and bring halos, the stats are reduced over the ranks, and the trajectory is
// the one process's, bit for bit. download() gathers the whole state on every rank, and a
// checkpoint (export_resume_state) holds the one-process arrays, so a run restores on any
// number of ranks. Every pressure model, dfsph's solves included (sph_simulation_dfsph.cpp).
#include <array>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "engine/grid/hash_grid.h"
#include "engine/kernels/backend.h"
#include "engine/sph/sph_comm.h"
#include "engine/sph/sph_params.h"
#include "engine/sph/sph_particles.h"
#include "engine/sph/sph_ranks.h"
#include "engine/sph/sph_watchdog.h"

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

struct SphStepStats {
  double max_speed = 0, max_accel = 0, max_drift = 0;  // m/s, m/s^2, m
  double max_density = 0;                              // kg/m^3
  uint32_t max_candidates = 0, max_neighbors = 0, outside = 0;
};

enum class SphStage : uint8_t { grid, density, forces, integrate, solve, count };

// The dfsph model's pressure solves since the start (engine/kernels/dfsph_kernels.h).
struct SphSolveStats {
  uint64_t steps = 0;               // steps that ran both solves
  uint64_t density_iterations = 0;  // summed over the steps
  uint64_t divergence_iterations = 0;
  uint64_t unconverged = 0;       // solves that stopped at dfsph_max_iterations
  double last_density_error = 0;  // the last density solve's final mean residual
  double last_divergence_error = 0;
};
const char* to_string(SphStage s);

// The largest residual sum of a DFSPH solve (kDfsphResidualScale units over `movers` particles)
// whose mean is at most `target`: the convergence test as the integer comparison the kernels
// make (DfsphParams::stop_units).
uint64_t dfsph_stop_units(double target, uint32_t movers);

// Everything the simulation's next steps depend on besides its scene, for a checkpoint
// (sph_checkpoint.h): the committed device arrays in the order of the last grid rebuild (the
// next step's neighbour sums run in that order), the host's step control and the watchdog's
// baseline. A simulation built from the same scene and given this continues the trajectory the
// exporting one would have taken, bit for bit on one backend.
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
  // A block that a call to run() left open (see the header, "Blocks"): its dt limit and the
  // stats words accumulated on the device so far (kSphStatWords; empty when none is open).
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

class SphSimulation {
 public:
  // `comm`: the ranks sharing the simulation (see the header); null or one rank: this process
  // alone.
  SphSimulation(Backend& backend, const SphScene& scene, SphComm* comm = nullptr);

  // Advances the simulation by one step: dt (fixed, possibly split into sub-steps by the CFL
  // guard) or the adaptive dt. Throws masav::Error (state left at the last good step).
  void step();
  // Up to `steps` steps, stopping early once time() reaches t_end; in blocks (see the header).
  // Returns the steps taken.
  uint64_t run(uint64_t steps, double t_end = std::numeric_limits<double>::infinity());
  // Steps per stats read in run(): 1 to kMaxBlockSteps (1 when no checkpoint fits).
  static constexpr uint32_t kMaxBlockSteps = 64;
  void set_block_steps(uint32_t k);
  uint32_t block_steps() const;
  uint64_t block_replays() const { return block_replays_; }  // blocks rolled back and replayed
  // RK4: whether its later evaluations walk the first one's reach masks (SphReach).
  bool keeps_reach_masks() const { return reach_rows_.valid(); }
  // From now on every RK4 evaluation walks the inflated cells, as where the masks do not fit:
  // the tests' way to compare the two walks.
  void drop_reach_masks() { reach_rows_ = {}; }
  // Whether sph_forces reads sph_density's neighbour state (kSphStateStride): where the
  // backend's SphTuning::neighbor_state allows and it fits.
  bool keeps_neighbor_state() const { return neighbor_state_.valid(); }

  double time() const { return time_; }
  uint64_t steps() const { return steps_; }
  uint64_t substeps() const { return substeps_; }  // integrator steps actually taken
  uint64_t retries() const { return retries_; }    // steps the guard rejected and retried
  double last_dt() const { return last_dt_; }
  // The limit the CFL conditions give for the current state (s).
  double dt_limit() const;

  const SphScene& scene() const { return scene_; }
  const SphParticles& layout() const { return layout_; }  // spacing, h, mass, counts
  uint32_t particle_count() const { return n_; }          // all ranks' together
  // The particles this rank's buffers hold: all of them in one process; on several ranks its
  // share with room for halos, grown (never shrunk) when it takes more (see reserve).
  uint32_t capacity() const { return capacity_; }
  uint64_t capacity_growths() const { return capacity_growths_; }
  // Whether the last error came from the simulation's own checks (the CFL guard, the watchdog,
  // a non-finite state, neighbour overflow), which decide on values reduced over the ranks: then
  // every rank raised it at the same step, and they can still write the state together.
  bool failed_together() const { return failed_together_; }
  // The decomposition when the simulation runs on several ranks; null otherwise.
  const SphRanks* ranks() const { return ranks_.get(); }
  SphRanks* ranks() { return ranks_.get(); }
  SphStepParams step_params() const { return step_params_; }
  const SphStepStats& last_stats() const { return stats_; }
  const SphSolveStats& solve_stats() const { return solve_stats_; }  // dfsph only
  // dfsph: the residual reads (host waits) of the solves so far, and whether a solve queues
  // several iterations per read (on by default; off: one per iteration, the same bits).
  uint64_t dfsph_residual_reads() const { return dfsph_residual_reads_; }
  void set_dfsph_queued_iterations(bool on) { dfsph_queue_ = on; }
  Backend& backend() { return backend_; }

  // Current state, in particle-id order, with density and pressure at these positions (on
  // several ranks: every rank's particles, on every rank).
  SphState download();
  // This rank's own particles (every particle in one process), in the order of the last grid
  // rebuild, with their ids: what a rank writes as its piece of a snapshot.
  SphState download_own(std::vector<uint32_t>& ids);
  // The committed state on the backend, for a renderer to bind without a copy: in the order of
  // the last grid rebuild (not particle-id order); positions' w = inverse mass scale. density()
  // and pressure() are index-aligned with positions() and belong to the last force pass (at
  // most one step old) -- until download() evaluates at a re-sorted scratch copy.
  const Buffer<Real4>& positions() const { return pos_; }
  const Buffer<Real4>& velocities() const { return vel_; }
  const Buffer<Real>& density() const { return density_; }
  const Buffer<Real>& pressure() const { return pressure_; }
  // Replaces the velocities (indexed by particle id), e.g. to start from a velocity field.
  void set_velocities(const std::vector<Vec4d>& by_id);

  // The state a checkpoint keeps (sph_simulation_resume.cpp); restore_resume_state takes one
  // exported by a simulation of the same scene (throws masav::Error naming the field that does not
  // fit).
  SphResumeState export_resume_state();
  void restore_resume_state(const SphResumeState& r);

  // Device time per stage, summed since the last reset (recorded when profiling is on).
  void set_profiling(bool on) { profiling_ = on; }
  std::array<double, size_t(SphStage::count)> stage_ms() const { return stage_ms_; }
  void reset_stage_ms() { stage_ms_.fill(0.0); }

 private:
  struct Attempt {
    bool ok = true;
    bool overflow = false;  // neighbour candidates beyond max_candidates
    bool watchdog = false;  // beyond a watchdog bound: stop, do not retry
    std::string reason;
  };
  static constexpr uint64_t kMaxSubsteps = 1u << 20;  // of one fixed-dt step (CFL guard)
  // What a rolled-back block restores on the host.
  struct HostState {
    double time, last_dt, adaptive_dt;
    uint64_t steps, substeps;
    SphStepStats stats, lag_stats;
    bool accel_valid, fields_current, block_open;
    double block_limit;
    uint64_t next_energy_check;
    SphRankLayout ranks;  // the committed layout, on several ranks
  };
  struct Checkpoint {
    Buffer<Real4> pos, vel, accel;
    Buffer<uint32_t> ids;
  };
  // A state's copies queued by queue_state_reads (read_async tickets; 0: taken).
  struct StateReads {
    uint64_t pos = 0, vel = 0, ids = 0, rho = 0, pr = 0, acc = 0;
  };
  // A block run() submitted and whose stats it has not taken yet (see the header, "Blocks").
  struct PendingBlock {
    uint64_t ticket = 0;  // DeviceApi::read_async of its stats
    HostState start;      // the host state at its start; its state on the device: checkpoint
    int checkpoint = 0;   // checkpoints_[checkpoint]
    uint64_t taken = 0;   // steps recorded
    double max_dt = 0;
    bool continuing = false;  // a later part of a block run() left open
    double t_end = 0;         // run()'s, for a replay
    // The energy watchdog's check of its end state, queued behind it where one is due there.
    std::optional<StateReads> probe;
  };
  void rebuild_moving(const Buffer<Real4>& x, Buffer<Real4>& x_sorted, const Buffer<Real4>& v,
                      Buffer<Real4>& v_sorted, const Buffer<uint32_t>& ids,
                      Buffer<uint32_t>& ids_sorted);
  void sort_state();  // rebuild on pos_ with pos_, vel_, ids_ moved into cell order
  // The particles a rank's buffers start with room for, and the refusals, before anything is
  // allocated, of a count the device cannot hold: one buffer of positions, then the memory
  // budget (sph_simulation_buffers.cpp).
  static uint32_t initial_capacity(uint64_t particles, int ranks);
  static void check_capacity(const Backend& b, const SphScene& s, int ranks);
  static void check_buffer_size(const Backend& b, uint64_t particles, int ranks);
  void allocate_particle_buffers();
  // On several ranks: room for `local` particles in every per-particle buffer, the contents
  // kept (sph_simulation_buffers.cpp).
  void reserve(uint32_t local);
  // On several ranks: the grid of the staged layout's arrays, already in cell order (x), and the
  // kernels' particle counts and own ranges.
  void use_rank_layout(const Buffer<Real4>& x);
  SphState download_ranks();
  // For the scope of an evaluation outside the steps (download()): the stats words start from
  // zero and, where run() left a block open, get the block's back at the end (its maxima choose
  // the next block's dt: reading the state must not change the trajectory).
  class StatsKeeper {
   public:
    explicit StatsKeeper(SphSimulation& sim);
    ~StatsKeeper();
    StatsKeeper(const StatsKeeper&) = delete;
    StatsKeeper& operator=(const StatsKeeper&) = delete;

   private:
    SphSimulation& sim_;
    uint64_t ticket_ = 0;  // the open block's stats words (DeviceApi::read_async)
  };
  // download() in two halves (one process): the state's copies queued behind the work so far
  // (density evaluated first where the fields are stale, the open block's stats kept by `keep`),
  // then taken with one wait. drop_state takes them unread.
  StateReads queue_state_reads(std::optional<StatsKeeper>& keep);
  SphState take_state(StateReads& r);
  SphState take_state_reads(StateReads& r);  // take_state without the clean-up on an error
  // dfsph's pressure from its density solve's kappa sums (in place) and the densities.
  void dfsph_pressure(std::vector<double>& kappa, const std::vector<double>& rho) const;
  void drop_state(StateReads& r);
  void refresh_fields_ranks();  // density and pressure at the committed state's positions
  [[noreturn]] void fail_non_finite_ranks(double dt);
  // Density and forces at x, v; `reach`: how sph_density uses the reach masks, where kept.
  void evaluate(const Buffer<Real4>& x, const Buffer<Real4>& v, SphReach reach = SphReach::none);
  Buffer<uint32_t>* neighbor_rows();  // null where the masks are not kept
  // sph_density's and sph_forces's buffers at x, v in the step's own forms (the row masks and
  // the neighbour state where kept): every evaluation uses them, so a state read between steps
  // runs the pipelines the steps built and compiles none mid-run.
  SphDensityIO density_io(const Buffer<Real4>& x, const Buffer<Real4>& v);
  SphForcesIO forces_io(const Buffer<Real4>& x, const Buffer<Real4>& v);
  void integrate(SphStageOp op, double dt, const Buffer<Real4>& x0, const Buffer<Real4>& v0,
                 const Buffer<Real4>* vk, Buffer<Real4>* x_out, Buffer<Real4>& v_out,
                 Buffer<Real4>* sum_x, Buffer<Real4>* sum_v);
  void record_step(double dt);  // the integrator's kernels for one step of dt
  // Whether stats `w` / `s` of a step (or a block) of at most `dt` are acceptable.
  Attempt judge(const uint32_t w[kSphStatWords], const SphStepStats& s, double dt) const;
  void commit(double dt);      // the recorded step's results become the state
  Attempt attempt(double dt);  // one integrator step, committed if accepted
  // Records up to k steps of the block the current step falls in and submits them (see the
  // header, "Blocks"); settles the block before it.
  void record_block(uint64_t k, double t_end);
  // Takes the pending block's stats: accepts it, or rolls it back and replays it step by step.
  void settle_block();
  // Settles `p`; `later`: the block recorded after it, not yet pending, or null. False: `p` was
  // rolled back and replayed, and `later` dropped with it (its read taken unseen).
  bool settle(PendingBlock& p, PendingBlock* later);
  void drop_block(PendingBlock& p);  // its reads, unread
  // Whether run() keeps one block pending while it records the next.
  bool pipelines_blocks() const;
  HostState save_host_state() const;
  void restore_host_state(const HostState& h);
  // The watchdog's energy check, every SphWatchdog::kEnergyEvery steps (see sph_watchdog.h).
  void watch_energy();
  // The check of state `s`, taken at host state `at` (the current one, or a pending block's
  // end): passes (the last good state, the next check's step) or restores the last good state
  // and throws.
  void check_energy(const SphState& s, const HostState& at);
  void set_watchdog_baseline(const SphState& s);
  bool leapfrog_accel() const;  // accel_ is part of the state (leapfrog's carried force)
  void take_checkpoint(Checkpoint& c);
  void restore_checkpoint(const Checkpoint& c, const HostState& h);
  // attempt() with the guard's retries at half the step; `whole` covers all of dt.
  void advance(double dt, int depth, bool whole);
  void step_euler(double dt, SphStageOp op);
  void step_rk4(double dt);
  void step_leapfrog(double dt);
  // dfsph (sph_simulation_dfsph.cpp): density and factor at x (the grid sorted at x), one
  // solve on velocities v with its kappa sum, the step.
  void allocate_dfsph();
  void dfsph_fields(const Buffer<Real4>& x);
  DfsphParams dfsph_params(DfsphSolve solve, double dt) const;
  void dfsph_solve(DfsphSolve solve, double dt, const Buffer<Real4>& x, Buffer<Real4>& v,
                   Buffer<Real>& kappa_sum);
  void step_dfsph(double dt);
  bool dfsph() const { return scene_.model == SphPressureModel::dfsph; }
  SphStepStats read_stats(uint32_t words[kSphStatWords]);
  // The stats of the words just read (reduced over the ranks first, in place).
  SphStepStats stats_from_words(uint32_t words[kSphStatWords]);
  [[noreturn]] void fail_non_finite(double dt);
  // The error naming particle `id` (UINT32_MAX: unknown) that entered the step non-finite
  // (`origin`) or got so in it.
  [[noreturn]] void throw_non_finite(double dt, uint32_t id, bool origin);
  // Throws e as an error of the simulation's own checks (failed_together()).
  [[noreturn]] void fail_together(const Error& e);
  void mark(SphStage ended);
  void collect_stage_times();
  double limit_for(const SphStepStats& s) const;
  double courant_scale() const;  // the integrator's share of the Courant number

  Backend& backend_;
  SphScene scene_;
  SphParticles layout_;
  uint32_t n_ = 0;
  uint32_t capacity_ = 0;  // particles per per-particle buffer (see capacity())
  uint64_t capacity_growths_ = 0;
  bool failed_together_ = false;
  SphStepParams step_params_;
  double cell_size_ = 0;
  double skin_ = 0;  // m: allowed drift of a stage from the rebuild positions (RK4)
  HashGrid grid_;
  std::unique_ptr<SphRanks> ranks_;  // several ranks only

  // Committed state in the order of the last rebuild, and scratch.
  Buffer<Real4> pos_, vel_, xs_, vs_, sum_x_, sum_v_, ta_, tb_, tc_, accel_;
  Buffer<uint32_t> ids_, ids_t_, stats_buf_;
  // sph_density's neighbour row masks for sph_forces at the same positions (every evaluate()
  // runs both); empty where they are not kept (see keeps_neighbor_rows).
  Buffer<uint32_t> neighbor_rows_;
  // RK4: sph_density's reach masks of the step's first evaluation (within the grid's cell size,
  // h + skin rounded up), which its other three walk (SphReach); empty where not kept (see
  // keeps_reach_rows).
  Buffer<uint32_t> reach_rows_;
  // sph_density's neighbour state (kSphStateStride) for sph_forces at the same positions and
  // velocities; empty where not kept (see neighbor_state_fits).
  Buffer<Real4> neighbor_state_;
  Buffer<Real> density_, pressure_;
  // dfsph: the factor at pos_ (or the step's new positions), one iteration's kappa, each
  // solve's kappa sum in pos_'s order (warm starts) and in the new order, the residual slots.
  Buffer<Real> factor_, kappa_, kappa_density_, kappa_divergence_, kappa_density_t_,
      kappa_divergence_t_;
  Buffer<uint32_t> residual_;
  bool kappa_warm_ = false;  // the kappa sums hold a previous step's (in pos_'s order)
  uint32_t min_neighbors_ = 0;
  // Iterations each solve (divergence, density) took last: how many the next queues before it
  // reads a residual.
  uint32_t last_iterations_[2] = {0, 0};
  bool dfsph_queue_ = true;
  uint64_t dfsph_residual_reads_ = 0;
  SphSolveStats solve_stats_;
  // The states at the start of run()'s pending block and of the one after it; empty where they
  // do not fit (the second: where it does not, or on several ranks).
  std::array<Checkpoint, 2> checkpoints_;
  std::optional<PendingBlock> pending_;
  uint32_t block_steps_ = 8;
  // The block of the fixed schedule that run() left open: its dt limit (see the header).
  bool block_open_ = false;
  double block_limit_ = 0;
  SphWatchdog watchdog_;
  uint64_t next_energy_check_ = 0;
  struct GoodState {  // the last state that passed the energy check, by particle id
    std::vector<Vec4d> positions, velocities;
    double time = 0, last_dt = 0;
    uint64_t steps = 0, substeps = 0;
    SphStepStats stats;
  } good_;
  uint64_t block_replays_ = 0;
  bool accel_valid_ = false;     // leapfrog: accel_ holds a(pos_) in pos_'s order
  bool fields_current_ = false;  // density_, pressure_, accel_ belong to pos_ (pos_'s order)

  double time_ = 0, last_dt_ = 0, adaptive_dt_ = 0;
  uint64_t steps_ = 0, substeps_ = 0, retries_ = 0;
  SphStepStats stats_;
  SphStepStats lag_stats_;  // the stats before stats_' block (see the header, "Blocks")

  bool profiling_ = false;
  std::vector<std::pair<TimestampId, SphStage>> marks_;
  TimestampId first_mark_ = 0;
  std::array<double, size_t(SphStage::count)> stage_ms_{};
};

}  // namespace masav
