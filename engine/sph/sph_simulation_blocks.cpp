// SphSimulation::run: steps in blocks whose stats are read asynchronously (see the header,
// "Blocks").
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <optional>
#include <utility>

#include "engine/sph/sph_simulation.h"

namespace masav {

SphSimulation::HostState SphSimulation::save_host_state() const {
  return {time_,
          last_dt_,
          adaptive_dt_,
          steps_,
          substeps_,
          stats_,
          lag_stats_,
          accel_valid_,
          fields_current_,
          block_open_,
          block_limit_,
          next_energy_check_,
          ranks_ ? ranks_->committed() : SphRankLayout{}};
}

void SphSimulation::restore_host_state(const HostState& h) {
  time_ = h.time;
  last_dt_ = h.last_dt;
  adaptive_dt_ = h.adaptive_dt;
  steps_ = h.steps;
  substeps_ = h.substeps;
  stats_ = h.stats;
  lag_stats_ = h.lag_stats;
  accel_valid_ = h.accel_valid;
  fields_current_ = h.fields_current;
  block_open_ = h.block_open;
  block_limit_ = h.block_limit;
  next_energy_check_ = h.next_energy_check;
  if (ranks_) ranks_->restore(h.ranks);
}

void SphSimulation::set_block_steps(uint32_t k) {
  if (k < 1 || k > kMaxBlockSteps)
    throw_invalid("sph", "block steps", std::to_string(k),
                  fmt::format("1 to {} (1 = read the stats after every step)", kMaxBlockSteps));
  block_steps_ = k;
}

uint32_t SphSimulation::block_steps() const {
  return checkpoints_[0].pos.valid() ? block_steps_ : 1;  // none kept for dfsph
}

bool SphSimulation::pipelines_blocks() const {
  return !ranks_ && checkpoints_[1].pos.valid();
}

uint64_t SphSimulation::run(uint64_t steps, double t_end) {
  const uint64_t first = steps_;
  try {
    for (;;) {
      while (steps_ - first < steps && time_ < t_end) {
        const uint64_t b = block_steps();
        if (b > 1 && !profiling_) {
          // The energy check reads the state it checks: settled, at the end of a block.
          if (pending_ && steps_ >= next_energy_check_) settle_block();
          if (!pending_) watch_energy();
          // To the end of the block of the fixed schedule this step falls in.
          record_block(std::min<uint64_t>(steps - (steps_ - first), b - steps_ % b), t_end);
        } else {
          if (pending_) settle_block();
          step();
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
  watch_energy();
  return steps_ - first;
}

bool SphSimulation::leapfrog_accel() const {
  return scene_.integrator == SphIntegrator::leapfrog && accel_valid_;
}

void SphSimulation::take_checkpoint(Checkpoint& c) {
  backend_.copy(pos_, c.pos);
  backend_.copy(vel_, c.vel);
  backend_.copy(ids_, c.ids);
  if (leapfrog_accel()) backend_.copy(accel_, c.accel);
}

void SphSimulation::restore_checkpoint(const Checkpoint& c, const HostState& h) {
  restore_host_state(h);
  backend_.copy(c.pos, pos_);
  backend_.copy(c.vel, vel_);
  backend_.copy(c.ids, ids_);
  if (leapfrog_accel()) backend_.copy(c.accel, accel_);
  fields_current_ = false;  // density_ and pressure_ belong to a later state
}

void SphSimulation::record_block(uint64_t k, double t_end) {
  // A later part of a block keeps its dt limit and adds to its stats on the device.
  const bool continuing = block_open_ && steps_ % block_steps() != 0;
  // Block b's limit is block b-2's stats: the last taken where block b-1's first part is
  // pending, else the ones before them (b-1's first part moved them back a place when taken).
  const double limit = continuing
                           ? block_limit_
                           : limit_for(pending_ && !pending_->continuing ? stats_ : lag_stats_);
  uint64_t parts = 1;
  bool single = false;  // a step of step()'s own decides (and stops with its message)
  if (scene_.dt && *scene_.dt > limit && scene_.cfl_guard != SphCflGuard::off) {
    const double want = std::ceil(*scene_.dt / limit);
    single = scene_.cfl_guard == SphCflGuard::stop || want > double(kMaxSubsteps) ||
             *scene_.dt / want < scene_.dt_min;
    parts = uint64_t(want);
  }
  // The adaptive dt only grows within a block (the limit is the block's start's), so only its
  // first step can fall below dt_min.
  if (!scene_.dt && std::min({limit, adaptive_dt_ * 1.25, scene_.dt_max}) < scene_.dt_min)
    single = true;
  if (single) {
    if (pending_) {
      settle_block();  // then the loop in run() comes back here with it settled
      return;
    }
    step();
    return;
  }
  const int slot = pending_ ? 1 - pending_->checkpoint : 0;
  PendingBlock p;
  p.start = save_host_state();
  p.checkpoint = slot;
  p.continuing = continuing;
  // The block's work as one unit where the backend can (a CUDA graph). Not with ranks: their
  // exchanges go through the host.
  std::optional<CaptureScope> capture;
  if (pipelines_blocks()) capture.emplace(backend_);
  take_checkpoint(checkpoints_[size_t(slot)]);
  if (!continuing) backend_.fill(stats_buf_, 0u);
  block_limit_ = limit;
  for (; p.taken < k && time_ < t_end; ++p.taken) {
    if (scene_.dt) {
      const double dt = *scene_.dt / double(parts);
      for (uint64_t q = 0; q < parts; ++q) {
        record_step(dt);
        commit(dt);
      }
      p.max_dt = dt;
    } else {
      const double dt = std::min({limit, adaptive_dt_ * 1.25, scene_.dt_max});
      record_step(dt);
      commit(dt);
      adaptive_dt_ = dt;
      p.max_dt = std::max(p.max_dt, dt);
    }
    ++steps_;
  }
  block_open_ = steps_ % block_steps() != 0;  // until a rollback says otherwise
  p.t_end = t_end;
  if (capture) capture->commit();
  p.ticket = backend_.read_async(stats_buf_.impl(), kSphStatWords * sizeof(uint32_t));
  if (pipelines_blocks() && !block_open_ && steps_ >= next_energy_check_) {
    // The energy check due at this block's end: its state queued behind it and checked when its
    // stats are taken, so the check waits for nothing (a rollback restores the next check).
    std::optional<StatsKeeper> none;  // no block is open: no stats to keep
    p.probe = queue_state_reads(none);
    next_energy_check_ = steps_ + SphWatchdog::kEnergyEvery;
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

void SphSimulation::drop_block(PendingBlock& p) {
  backend_.discard_read(std::exchange(p.ticket, 0));
  if (p.probe) drop_state(*p.probe);
  p.probe.reset();
}

void SphSimulation::settle_block() {
  if (!pending_) return;
  PendingBlock p = std::move(*pending_);
  pending_.reset();
  settle(p, nullptr);
}

bool SphSimulation::settle(PendingBlock& p, PendingBlock* later) {
  const uint64_t ticket = p.ticket;
  p.ticket = 0;
  const std::vector<uint8_t> bytes = backend_.take_read(ticket);
  uint32_t w[kSphStatWords];
  std::memcpy(w, bytes.data(), sizeof w);
  const SphStepStats s = stats_from_words(w);
  // A fixed dt is also held to the limit of the block's own stats: step() checks (stop) or
  // splits (reduce) each step against the limit of the step before, which the block's maxima
  // bound from below.
  const bool fixed_within_limit =
      !scene_.dt || scene_.cfl_guard == SphCflGuard::off || p.max_dt <= limit_for(s);
  if (fixed_within_limit && judge(w, s, p.max_dt).ok) {
    // A block's first part moves the last stats back a place; its later parts add to them.
    if (!p.continuing) lag_stats_ = stats_;
    stats_ = s;
    if (later) {  // it started from this block's end, before these stats were known
      later->start.stats = stats_;
      later->start.lag_stats = lag_stats_;
    }
    if (p.probe) {
      const SphState end = take_state(*p.probe);
      p.probe.reset();
      try {
        check_energy(end, later ? later->start : save_host_state());
      } catch (...) {
        if (later) drop_block(*later);  // the state is back at the last good one
        throw;
      }
    }
    return true;
  }
  // Something went wrong within the block: replay it step by step from its start, reading the
  // stats after every step, so the guard retries or stops at the very step, as step() does.
  // A block recorded after it started from its end: it goes too, its stats unread.
  if (p.probe) drop_state(*p.probe);
  if (later) drop_block(*later);
  restore_checkpoint(checkpoints_[size_t(p.checkpoint)], p.start);
  block_open_ = false;  // a replay ends the block where it stands
  ++block_replays_;
  for (uint64_t replayed = 0; replayed < p.taken && time_ < p.t_end; ++replayed) step();
  return false;
}

}  // namespace masav
