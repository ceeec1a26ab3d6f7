// SphBlockScheduler: run()'s blocks (see the header), their checkpoints, their asynchronous
// stats reads and the replay of a block the guard rejects.
#include "engine/sph/sph_block_scheduler.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <optional>
#include <utility>

#include "engine/core/error.h"
#include "engine/sph/sph_device_state.h"
#include "engine/sph/sph_energy_watch.h"
#include "engine/sph/sph_field_evaluator.h"
#include "engine/sph/sph_step_control.h"

namespace masav {

SphBlockScheduler::HostState SphBlockScheduler::save_host_state() const {
  return {c_.progress, c_.ranks ? c_.ranks->committed() : SphRankLayout{}};
}

void SphBlockScheduler::restore_host_state(const HostState& h) {
  c_.progress = h.progress;
  if (c_.ranks) c_.ranks->restore(h.ranks);
}

void SphBlockScheduler::set_block_steps(uint32_t k) {
  if (k < 1 || k > kMaxBlockSteps)
    throw_invalid("sph", "block steps", std::to_string(k),
                  fmt::format("1 to {} (1 = read the stats after every step)", kMaxBlockSteps));
  block_steps_ = k;
}

void SphBlockScheduler::restore(uint32_t block_steps, uint64_t block_replays) {
  block_steps_ = block_steps;
  block_replays_ = block_replays;
}

uint32_t SphBlockScheduler::block_steps() const {
  return c_.device.checkpoints[0].pos.valid() ? block_steps_ : 1;  // none kept for dfsph
}

bool SphBlockScheduler::pipelines_blocks() const {
  return !c_.ranks && c_.device.checkpoints[1].pos.valid();
}

uint64_t SphBlockScheduler::run(uint64_t steps, double t_end) {
  const uint64_t first = c_.progress.steps;
  try {
    for (;;) {
      while (c_.progress.steps - first < steps && c_.progress.time < t_end) {
        const uint64_t b = block_steps();
        if (b > 1 && !c_.fields.profiling()) {
          // The energy check reads the state it checks: settled, at the end of a block.
          if (pending_ && c_.progress.steps >= c_.progress.next_energy_check) settle_block();
          if (!pending_) control_.watch_energy();
          // To the end of the block of the fixed schedule this step falls in.
          record_block(
              std::min<uint64_t>(steps - (c_.progress.steps - first), b - c_.progress.steps % b),
              t_end);
        } else {
          if (pending_) settle_block();
          control_.step();
        }
      }
      // A block rolled back at the end may leave steps (or time) to go.
      if (!pending_) break;
      settle_block();
    }
  } catch (...) {
    // An error while a block was pending (a device fault): its stats will not be taken.
    if (pending_) {
      drop_block(*pending_);
      pending_.reset();
    }
    throw;
  }
  control_.watch_energy();
  return c_.progress.steps - first;
}

bool SphBlockScheduler::leapfrog_accel() const {
  return c_.scene.integrator == SphIntegrator::leapfrog && c_.progress.accel_valid;
}

void SphBlockScheduler::take_checkpoint(SphBlockCheckpoint& cp, bool continuing) {
  c_.backend.copy(c_.device.pos, cp.pos);
  c_.backend.copy(c_.device.vel, cp.vel);
  c_.backend.copy(c_.device.ids, cp.ids);
  if (leapfrog_accel()) c_.backend.copy(c_.device.accel, cp.accel);
  if (continuing) c_.backend.copy(c_.device.stats, cp.stats);
}

void SphBlockScheduler::restore_checkpoint(const SphBlockCheckpoint& cp, const HostState& h,
                                           bool continuing) {
  restore_host_state(h);
  c_.backend.copy(cp.pos, c_.device.pos);
  c_.backend.copy(cp.vel, c_.device.vel);
  c_.backend.copy(cp.ids, c_.device.ids);
  if (leapfrog_accel()) c_.backend.copy(cp.accel, c_.device.accel);
  if (continuing) c_.backend.copy(cp.stats, c_.device.stats);
  c_.progress.fields_current = false;  // density and pressure belong to a later state
}

void SphBlockScheduler::record_block(uint64_t k, double t_end, const Retake* retake) {
  // A later part of a block keeps its dt limit and adds to its stats on the device.
  const bool continuing = retake ? retake->continuing
                                 : c_.progress.block_open && c_.progress.steps % block_steps() != 0;
  // Block b's limit is block b-2's stats: the last taken where block b-1's first part is
  // pending, else the ones before them (b-1's first part moved them back a place when taken).
  const double limit =
      retake       ? retake->limit
      : continuing ? c_.progress.block_limit
                   : control_.limit_for(pending_ && !pending_->continuing ? c_.progress.stats
                                                                          : c_.progress.lag_stats);
  uint64_t parts = 1;
  bool single = false;  // a step of step()'s own decides (and stops with its message)
  if (c_.scene.dt && *c_.scene.dt > limit && c_.scene.cfl_guard != SphCflGuard::off) {
    const double want = std::ceil(*c_.scene.dt / limit);
    single = c_.scene.cfl_guard == SphCflGuard::stop ||
             want > double(SphStepControl::kMaxSubsteps) || *c_.scene.dt / want < c_.scene.dt_min;
    parts = uint64_t(want);
  }
  // The adaptive dt only grows within a block (the limit is the block's start's), so only its
  // first step can fall below dt_min.
  if (!c_.scene.dt &&
      std::min({limit, c_.progress.adaptive_dt * 1.25, c_.scene.dt_max}) < c_.scene.dt_min)
    single = true;
  if (single) {
    if (pending_) {
      settle_block();  // then the loop in run() comes back here with it settled
      return;
    }
    control_.step();
    return;
  }
  const int slot = pending_ ? 1 - pending_->checkpoint : 0;
  PendingBlock p;
  p.start = save_host_state();
  p.checkpoint = slot;
  p.continuing = continuing;
  p.limit = limit;
  // The block's work as one unit where the backend can (a CUDA graph). Not with ranks: their
  // exchanges go through the host.
  std::optional<CaptureScope> capture;
  if (pipelines_blocks()) capture.emplace(c_.backend);
  take_checkpoint(c_.device.checkpoints[size_t(slot)], continuing);
  if (!continuing) c_.backend.fill(c_.device.stats, 0u);
  c_.progress.block_limit = limit;
  for (; p.taken < k && c_.progress.time < t_end; ++p.taken) {
    if (c_.scene.dt) {
      const double dt = *c_.scene.dt / double(parts);
      for (uint64_t q = 0; q < parts; ++q) {
        control_.record(dt);
        control_.commit(dt);
      }
      p.max_dt = dt;
    } else {
      const double dt = std::min({limit, c_.progress.adaptive_dt * 1.25, c_.scene.dt_max});
      control_.record(dt);
      control_.commit(dt);
      c_.progress.adaptive_dt = dt;
      p.max_dt = std::max(p.max_dt, dt);
    }
    ++c_.progress.steps;
  }
  c_.progress.block_open =
      c_.progress.steps % block_steps() != 0;  // until a rollback says otherwise
  p.t_end = t_end;
  if (capture) capture->commit();
  p.ticket = c_.backend.read_async(c_.device.stats.impl(), kSphStatWords * sizeof(uint32_t));
  if (pipelines_blocks() && !c_.progress.block_open &&
      c_.progress.steps >= c_.progress.next_energy_check) {
    // The energy check due at this block's end: its state queued behind it and checked when its
    // stats are taken, so the check waits for nothing (a rollback restores the next check).
    std::optional<SphStatsKeeper> none;  // no block is open: no stats to keep
    p.probe = reads_.queue(none);
    c_.progress.next_energy_check = c_.progress.steps + SphWatchdog::kEnergyEvery;
  }
  if (pending_) {
    // The block before this one, finished by now or soon: take its stats while this one runs.
    PendingBlock before = std::move(*pending_);
    pending_.reset();
    bool kept = false;
    try {
      kept = settle(before, &p);
    } catch (...) {
      drop_block(p);
      throw;
    }
    if (!kept) return;  // rolled back and replayed, this block with it
  }
  pending_ = std::move(p);
  if (!pipelines_blocks()) settle_block();
}

void SphBlockScheduler::drop_block(PendingBlock& p) {
  c_.backend.discard_read(std::exchange(p.ticket, 0));
  if (p.probe) reads_.drop(*p.probe);
  p.probe.reset();
}

void SphBlockScheduler::settle_block() {
  if (!pending_) return;
  PendingBlock p = std::move(*pending_);
  pending_.reset();
  settle(p, nullptr);
}

bool SphBlockScheduler::settle(PendingBlock& p, PendingBlock* later) {
  const uint64_t ticket = p.ticket;
  p.ticket = 0;
  const std::vector<uint8_t> bytes = c_.backend.take_read(ticket);
  uint32_t w[kSphStatWords];
  std::memcpy(w, bytes.data(), sizeof w);
  const SphStepStats s = c_.fields.stats_from_words(w);
  // A fixed dt is also held to the limit of the block's own stats: step() checks (stop) or
  // splits (reduce) each step against the limit of the step before, which the block's maxima
  // bound from below.
  const bool fixed_within_limit =
      !c_.scene.dt || c_.scene.cfl_guard == SphCflGuard::off || p.max_dt <= control_.limit_for(s);
  if (fixed_within_limit && control_.judge(w, s, p.max_dt).ok) {
    // A block's first part moves the last stats back a place; its later parts add to them.
    if (!p.continuing) c_.progress.lag_stats = c_.progress.stats;
    c_.progress.stats = s;
    if (later) {  // it started from this block's end, before these stats were known
      later->start.progress.stats = c_.progress.stats;
      later->start.progress.lag_stats = c_.progress.lag_stats;
    }
    if (p.probe) {
      const SphState end = reads_.take(*p.probe);
      p.probe.reset();
      try {
        if (std::optional<Error> e = watch_.check(end, later ? later->start.progress : c_.progress))
          control_.fail_together(*e);
      } catch (...) {
        if (later) drop_block(*later);  // the state is back at the last good one
        throw;
      }
    }
    return true;
  }
  // Something went wrong within the part. A block recorded after it started from its end: it
  // goes too, its stats unread.
  if (p.probe) reads_.drop(*p.probe);
  if (later) drop_block(*later);
  restore_checkpoint(c_.device.checkpoints[size_t(p.checkpoint)], p.start, p.continuing);
  if (p.taken > 1) {
    retake_by_steps(p);
    return false;
  }
  // Its one step is replayed by step(), which reads the stats after it, so the guard retries or
  // stops at the very step, as it does without blocks.
  c_.progress.block_open = false;  // a replay ends the block where it stands
  ++block_replays_;
  if (c_.progress.time < p.t_end) control_.step();
  return false;
}

void SphBlockScheduler::retake_by_steps(const PendingBlock& p) {
  // The step the guard rejects is the first whose part of one step it rejects: taken again from
  // the part's start (restored, with the block's stats so far), a step per part, until one is
  // rejected and replayed or all are accepted. So a block ends at the same step whether run()
  // was asked for all its steps at once or for one at a time (a CSV row every step).
  const Retake first{p.continuing, p.limit};
  const uint64_t replays = block_replays_;
  for (uint64_t taken = 0;
       taken < p.taken && c_.progress.time < p.t_end && block_replays_ == replays; ++taken) {
    record_block(1, p.t_end, taken == 0 ? &first : nullptr);
    settle_block();
  }
}

}  // namespace masav
