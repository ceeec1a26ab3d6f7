#pragma once
// SphSimulation::run(): steps in blocks whose stats the host reads asynchronously, with the
// device-side checkpoints that let a rejected block be replayed step by step.
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
// (a block the guard rejects) ends a block where it stands. Where it stands must not depend on
// the split either: a rejected part of several steps is taken again as parts of one step each,
// judged on the block's stats so far, until one is rejected; that step is the one step() then
// replays, as it is when every part is one step long.
#include <cstdint>
#include <optional>

#include "engine/sph/sph_context.h"
#include "engine/sph/sph_ranks.h"
#include "engine/sph/sph_state_reads.h"

namespace masav {

class SphEnergyWatch;
class SphStepControl;
struct SphBlockCheckpoint;

class SphBlockScheduler {
 public:
  SphBlockScheduler(const SphContext& c, SphStepControl& control, SphStateReader& reads,
                    SphEnergyWatch& watch)
      : c_(c), control_(control), reads_(reads), watch_(watch) {}

  // Steps per stats read in run(): 1 to kMaxBlockSteps (1 when no checkpoint fits).
  static constexpr uint32_t kMaxBlockSteps = 64;
  // Up to `steps` steps, stopping early once time reaches t_end. Returns the steps taken.
  uint64_t run(uint64_t steps, double t_end);
  void set_block_steps(uint32_t k);
  uint32_t block_steps() const;
  // The block size asked for (a checkpoint's), whatever fits.
  uint32_t wanted_block_steps() const { return block_steps_; }
  // Blocks rolled back and replayed.
  uint64_t block_replays() const { return block_replays_; }
  // A checkpoint's counters, set as they were; `block_steps` as checked there.
  void restore(uint32_t block_steps, uint64_t block_replays);

 private:
  // What a rolled-back block restores on the host.
  struct HostState {
    SphProgress progress;
    SphRankLayout ranks;  // the committed layout, on several ranks
  };
  // A block run() submitted and whose stats it has not taken yet.
  struct PendingBlock {
    uint64_t ticket = 0;  // DeviceApi::read_async of its stats
    HostState start;      // the host state at its start; its state on the device: checkpoint
    int checkpoint = 0;   // SphDeviceState::checkpoints[checkpoint]
    uint64_t taken = 0;   // steps recorded
    double max_dt = 0;
    double limit = 0;         // its block's dt limit
    bool continuing = false;  // a later part of a block run() left open
    double t_end = 0;         // run()'s, for a replay
    // The energy watchdog's check of its end state, queued behind it where one is due there.
    std::optional<SphStateReads> probe;
  };

  // How a rejected part is taken again, a step at a time: as the part it was.
  struct Retake {
    bool continuing;
    double limit;
  };
  // Records up to k steps of the block the current step falls in and submits them; settles the
  // block before it. `retake`: the first step of a rejected part taken again.
  void record_block(uint64_t k, double t_end, const Retake* retake = nullptr);
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
  bool leapfrog_accel() const;  // accel is part of the state (leapfrog's carried force)
  void take_checkpoint(SphBlockCheckpoint& cp, bool continuing);
  void restore_checkpoint(const SphBlockCheckpoint& cp, const HostState& h, bool continuing);
  // Takes a rejected part of several steps again a step at a time (see settle()).
  void retake_by_steps(const PendingBlock& p);

  SphContext c_;
  SphStepControl& control_;
  SphStateReader& reads_;
  SphEnergyWatch& watch_;
  std::optional<PendingBlock> pending_;
  uint32_t block_steps_ = 8;
  uint64_t block_replays_ = 0;
};

}  // namespace masav
