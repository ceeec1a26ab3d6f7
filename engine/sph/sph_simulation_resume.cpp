// SphSimulation's resume state: export and restore of everything its next steps read (see
// SphResumeState), for checkpoints, gathered from and handed back to its parts.
#include <fmt/format.h>

#include <string>
#include <type_traits>

#include "engine/core/error.h"
#include "engine/sph/sph_dfsph_scheme.h"
#include "engine/sph/sph_rank_gather.h"
#include "engine/sph/sph_resume_checks.h"
#include "engine/sph/sph_simulation.h"

namespace masav {

SphResumeState SphSimulation::export_resume_state() {
  const SphDeviceState& d = device_;
  SphResumeState r;
  if (ranks_) {
    // The ranks' own particles in rank order: the one-process arrays (sph_ranks.h).
    r.positions = gather_own(backend_, *ranks_, d.pos);
    r.velocities = gather_own(backend_, *ranks_, d.vel);
    r.accel = gather_own(backend_, *ranks_, d.accel);
    r.ids = gather_own(backend_, *ranks_, d.ids);
    r.density = gather_own(backend_, *ranks_, d.density);
    r.pressure = gather_own(backend_, *ranks_, d.pressure);
  } else {
    r.positions = backend_.download(d.pos);
    r.velocities = backend_.download(d.vel);
    r.accel = backend_.download(d.accel);
    r.ids = backend_.download(d.ids);
    r.density = backend_.download(d.density);
    r.pressure = backend_.download(d.pressure);
  }
  if (context_.dfsph() && ranks_) {
    r.kappa_density = gather_own(backend_, *ranks_, d.kappa_density);
    r.kappa_divergence = gather_own(backend_, *ranks_, d.kappa_divergence);
  } else if (context_.dfsph()) {
    r.kappa_density = backend_.download(d.kappa_density);
    r.kappa_divergence = backend_.download(d.kappa_divergence);
  }
  const SphProgress& p = progress_;
  r.time = p.time;
  r.last_dt = p.last_dt;
  r.adaptive_dt = p.adaptive_dt;
  r.steps = p.steps;
  r.substeps = p.substeps;
  r.retries = control_.retries();
  r.block_replays = blocks_.block_replays();
  r.stats = p.stats;
  r.lag_stats = p.lag_stats;
  r.solve_stats = solve_stats();
  r.accel_valid = p.accel_valid;
  r.fields_current = p.fields_current;
  r.kappa_warm = dfsph_ && dfsph_->kappa_warm();
  r.block_steps = blocks_.wanted_block_steps();
  if (p.block_open) {
    r.block_limit = p.block_limit;
    r.block_stats = backend_.download(d.stats);
    if (ranks_) ranks_->reduce_stats(r.block_stats.data());
  }
  r.watchdog = watch_.bounds();
  r.next_energy_check = p.next_energy_check;
  const SphGoodState& good = watch_.good();
  r.good_positions = good.positions;
  r.good_velocities = good.velocities;
  r.good_time = good.time;
  r.good_last_dt = good.last_dt;
  r.good_steps = good.steps;
  r.good_substeps = good.substeps;
  r.good_stats = good.stats;
  return r;
}

void SphSimulation::restore_resume_state(const SphResumeState& r) {
  const uint32_t n = layout_.total();
  SphDeviceState& d = device_;
  // Every field, against this simulation's scene, before any of it reaches the device: a state
  // handed in by a program gets the checks a checkpoint's gets.
  validate_resume_state(scene_, r);
  std::vector<uint32_t> block_stats = r.block_stats;
  if (ranks_) {
    // Each rank takes an equal contiguous piece of the one-process arrays, whatever the number
    // of ranks that wrote them; the next rebuild moves the particles to their cells' owners.
    ranks_->balance(r.positions);
    const auto [b, e] = ranks_->share(n);
    auto piece = [b = b, e = e](const auto& v) {
      using V = std::decay_t<decltype(v)>;
      return V(v.begin() + std::ptrdiff_t(b), v.begin() + std::ptrdiff_t(e));
    };
    backend_.upload(d.pos, piece(r.positions));
    backend_.upload(d.vel, piece(r.velocities));
    backend_.upload(d.accel, piece(r.accel));
    backend_.upload(d.ids, piece(r.ids));
    backend_.upload(d.density, piece(r.density));
    backend_.upload(d.pressure, piece(r.pressure));
    if (context_.dfsph()) {
      backend_.upload(d.kappa_density, piece(r.kappa_density));
      backend_.upload(d.kappa_divergence, piece(r.kappa_divergence));
    }
    ranks_->restore({uint32_t(e - b), 0, uint32_t(e - b)});
    // The open block's stats are maxima, except the outside count, a sum: rank 0 keeps it.
    if (!block_stats.empty() && ranks_->rank() != 0) block_stats[kSphStatOutside] = 0;
  } else {
    backend_.upload(d.pos, r.positions);
    backend_.upload(d.vel, r.velocities);
    backend_.upload(d.accel, r.accel);
    backend_.upload(d.ids, r.ids);
    backend_.upload(d.density, r.density);
    backend_.upload(d.pressure, r.pressure);
    if (context_.dfsph()) {
      backend_.upload(d.kappa_density, r.kappa_density);
      backend_.upload(d.kappa_divergence, r.kappa_divergence);
    }
  }
  SphProgress& p = progress_;
  p.time = r.time;
  p.last_dt = r.last_dt;
  p.adaptive_dt = r.adaptive_dt;
  p.steps = r.steps;
  p.substeps = r.substeps;
  control_.set_retries(r.retries);
  blocks_.restore(r.block_steps, r.block_replays);
  p.stats = r.stats;
  p.lag_stats = r.lag_stats;
  if (dfsph_) dfsph_->restore(r.solve_stats, r.kappa_warm);
  p.accel_valid = r.accel_valid;
  p.fields_current = r.fields_current;
  p.block_open = !r.block_stats.empty();
  p.block_limit = r.block_limit;
  if (p.block_open) backend_.upload(d.stats, block_stats);
  watch_.bounds() = r.watchdog;
  p.next_energy_check = r.next_energy_check;
  watch_.good() = {r.good_positions, r.good_velocities, r.good_time, r.good_last_dt,
                   r.good_steps,     r.good_substeps,   r.good_stats};
  if (dfsph_) dfsph_->restore_fields();
}

}  // namespace masav
