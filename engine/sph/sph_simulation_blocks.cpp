// SphSimulation::run: steps in blocks with one stats read per block (see the header, "Blocks").
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "engine/sph/sph_simulation.h"

namespace masav {

struct SphSimulation::HostState {
  double time, last_dt, adaptive_dt;
  uint64_t steps, substeps;
  SphStepStats stats;
  bool accel_valid, fields_current;
  SphRankLayout ranks;  // the committed layout, on several ranks
};

SphSimulation::HostState SphSimulation::save_host_state() const {
  return {time_,        last_dt_,        adaptive_dt_,
          steps_,       substeps_,       stats_,
          accel_valid_, fields_current_, ranks_ ? ranks_->committed() : SphRankLayout{}};
}

void SphSimulation::restore_host_state(const HostState& h) {
  time_ = h.time;
  last_dt_ = h.last_dt;
  adaptive_dt_ = h.adaptive_dt;
  steps_ = h.steps;
  substeps_ = h.substeps;
  stats_ = h.stats;
  accel_valid_ = h.accel_valid;
  fields_current_ = h.fields_current;
  if (ranks_) ranks_->restore(h.ranks);
}

void SphSimulation::set_block_steps(uint32_t k) {
  if (k < 1 || k > kMaxBlockSteps)
    throw_invalid("sph", "block steps", std::to_string(k),
                  fmt::format("1 to {} (1 = read the stats after every step)", kMaxBlockSteps));
  block_steps_ = k;
}

uint32_t SphSimulation::block_steps() const {
  return checkpoint_.pos.valid() ? block_steps_ : 1;  // none kept for dfsph
}

uint64_t SphSimulation::run(uint64_t steps, double t_end) {
  uint64_t done = 0;
  while (done < steps && time_ < t_end) {
    const uint64_t b = block_steps();
    if (b > 1 && !profiling_) {
      // To the end of the block of the fixed schedule this step falls in.
      const uint64_t k = std::min<uint64_t>(steps - done, b - steps_ % b);
      done += run_block(k, t_end);
    } else {
      step();
      ++done;
    }
  }
  return done;
}

bool SphSimulation::leapfrog_accel() const {
  return scene_.integrator == SphIntegrator::leapfrog && accel_valid_;
}

void SphSimulation::take_checkpoint() {
  backend_.copy(pos_, checkpoint_.pos);
  backend_.copy(vel_, checkpoint_.vel);
  backend_.copy(ids_, checkpoint_.ids);
  if (leapfrog_accel()) backend_.copy(accel_, checkpoint_.accel);
}

void SphSimulation::restore_checkpoint(const HostState& h) {
  restore_host_state(h);
  backend_.copy(checkpoint_.pos, pos_);
  backend_.copy(checkpoint_.vel, vel_);
  backend_.copy(checkpoint_.ids, ids_);
  if (leapfrog_accel()) backend_.copy(checkpoint_.accel, accel_);
  fields_current_ = false;  // density_ and pressure_ belong to a later state
}

uint64_t SphSimulation::run_block(uint64_t k, double t_end) {
  // A later part of a block keeps its dt limit and adds to its stats on the device.
  const bool continuing = block_open_ && steps_ % block_steps() != 0;
  // dt for the whole block, as step() would choose it for the block's first step.
  const double limit = continuing ? block_limit_ : dt_limit();
  uint64_t parts = 1;
  if (scene_.dt && *scene_.dt > limit && scene_.cfl_guard != SphCflGuard::off) {
    const double want = std::ceil(*scene_.dt / limit);
    if (scene_.cfl_guard == SphCflGuard::stop || want > double(kMaxSubsteps) ||
        *scene_.dt / want < scene_.dt_min) {
      step();  // stops with step()'s message
      return 1;
    }
    parts = uint64_t(want);
  }
  // The adaptive dt only grows within a block (the limit is the block's start's), so only its
  // first step can fall below dt_min.
  if (!scene_.dt && std::min({limit, adaptive_dt_ * 1.25, scene_.dt_max}) < scene_.dt_min) {
    step();  // stops with step()'s message
    return 1;
  }
  const HostState start = save_host_state();
  take_checkpoint();
  if (!continuing) backend_.fill(stats_buf_, 0u);
  block_open_ = false;  // until this part is accepted
  block_limit_ = limit;
  double max_dt = 0;
  uint64_t taken = 0;
  for (; taken < k && time_ < t_end; ++taken) {
    if (scene_.dt) {
      const double dt = *scene_.dt / double(parts);
      for (uint64_t p = 0; p < parts; ++p) {
        record_step(dt);
        commit(dt);
      }
      max_dt = dt;
    } else {
      const double dt = std::min({limit, adaptive_dt_ * 1.25, scene_.dt_max});
      record_step(dt);
      commit(dt);
      adaptive_dt_ = dt;
      max_dt = std::max(max_dt, dt);
    }
    ++steps_;
  }
  uint32_t w[kSphStatWords];
  const SphStepStats s = read_stats(w);  // the block's one wait
  // A fixed dt is also held to the limit of the block's own stats: step() checks (stop) or
  // splits (reduce) each step against the limit of the step before, which the block's maxima
  // bound from below.
  const bool fixed_within_limit =
      !scene_.dt || scene_.cfl_guard == SphCflGuard::off || max_dt <= limit_for(s);
  if (fixed_within_limit && judge(w, s, max_dt).ok) {
    stats_ = s;
    block_open_ = steps_ % block_steps() != 0;
    watch_energy();
    return taken;
  }
  // Something went wrong within the block: replay it step by step from its start, reading the
  // stats after every step, so the guard retries or stops at the very step, as step() does.
  restore_checkpoint(start);
  ++block_replays_;
  uint64_t replayed = 0;
  for (; replayed < taken && time_ < t_end; ++replayed) step();
  return replayed;
}

}  // namespace masav
