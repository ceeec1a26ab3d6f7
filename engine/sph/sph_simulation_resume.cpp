// SphSimulation's resume state: export and restore of everything its next steps read (see
// SphResumeState), for checkpoints.
#include <fmt/format.h>

#include <string>
#include <type_traits>

#include "engine/core/error.h"
#include "engine/sph/sph_kernel_calls.h"
#include "engine/sph/sph_simulation.h"

namespace masav {
namespace {

template <class T>
void check_count(const std::vector<T>& v, size_t want, const char* field) {
  if (v.size() != want)
    throw_invalid("sph checkpoint", field, fmt::format("{} values", v.size()),
                  fmt::format("{} (one per particle of the scene)", want));
}

}  // namespace

SphResumeState SphSimulation::export_resume_state() {
  SphResumeState r;
  if (ranks_) {
    // The ranks' own particles in rank order: the one-process arrays (sph_ranks.h).
    r.positions = gather_own(backend_, *ranks_, pos_);
    r.velocities = gather_own(backend_, *ranks_, vel_);
    r.accel = gather_own(backend_, *ranks_, accel_);
    r.ids = gather_own(backend_, *ranks_, ids_);
    r.density = gather_own(backend_, *ranks_, density_);
    r.pressure = gather_own(backend_, *ranks_, pressure_);
  } else {
    r.positions = backend_.download(pos_);
    r.velocities = backend_.download(vel_);
    r.accel = backend_.download(accel_);
    r.ids = backend_.download(ids_);
    r.density = backend_.download(density_);
    r.pressure = backend_.download(pressure_);
  }
  if (dfsph() && ranks_) {
    r.kappa_density = gather_own(backend_, *ranks_, kappa_density_);
    r.kappa_divergence = gather_own(backend_, *ranks_, kappa_divergence_);
  } else if (dfsph()) {
    r.kappa_density = backend_.download(kappa_density_);
    r.kappa_divergence = backend_.download(kappa_divergence_);
  }
  r.time = time_;
  r.last_dt = last_dt_;
  r.adaptive_dt = adaptive_dt_;
  r.steps = steps_;
  r.substeps = substeps_;
  r.retries = retries_;
  r.block_replays = block_replays_;
  r.stats = stats_;
  r.lag_stats = lag_stats_;
  r.solve_stats = solve_stats_;
  r.accel_valid = accel_valid_;
  r.fields_current = fields_current_;
  r.kappa_warm = kappa_warm_;
  r.block_steps = block_steps_;
  if (block_open_) {
    r.block_limit = block_limit_;
    r.block_stats = backend_.download(stats_buf_);
    if (ranks_) ranks_->reduce_stats(r.block_stats.data());
  }
  r.watchdog = watchdog_;
  r.next_energy_check = next_energy_check_;
  r.good_positions = good_.positions;
  r.good_velocities = good_.velocities;
  r.good_time = good_.time;
  r.good_last_dt = good_.last_dt;
  r.good_steps = good_.steps;
  r.good_substeps = good_.substeps;
  r.good_stats = good_.stats;
  return r;
}

void SphSimulation::restore_resume_state(const SphResumeState& r) {
  check_count(r.positions, n_, "positions");
  check_count(r.velocities, n_, "velocities");
  check_count(r.accel, n_, "accelerations");
  check_count(r.ids, n_, "ids");
  check_count(r.density, n_, "density");
  check_count(r.pressure, n_, "pressure");
  check_count(r.kappa_density, dfsph() ? n_ : 0, "dfsph density kappa sums");
  check_count(r.kappa_divergence, dfsph() ? n_ : 0, "dfsph divergence kappa sums");
  check_count(r.good_positions, n_, "watchdog positions");
  check_count(r.good_velocities, n_, "watchdog velocities");
  if (!r.block_stats.empty() && r.block_stats.size() != kSphStatWords)
    throw_invalid("sph checkpoint", "open block's stats",
                  fmt::format("{} words", r.block_stats.size()),
                  fmt::format("{} (kSphStatWords)", kSphStatWords));
  // The ids index the state by particle (download()): a permutation of 0..n-1.
  std::vector<bool> seen(n_, false);
  for (const uint32_t id : r.ids) {
    if (id >= n_ || seen[id])
      throw_invalid("sph checkpoint", "ids", std::to_string(id),
                    fmt::format("each of 0 to {} exactly once", n_ - 1));
    seen[id] = true;
  }
  if (r.block_steps < 1 || r.block_steps > kMaxBlockSteps)
    throw_invalid("sph checkpoint", "block steps", std::to_string(r.block_steps),
                  fmt::format("1 to {}", kMaxBlockSteps));
  std::vector<uint32_t> block_stats = r.block_stats;
  if (ranks_) {
    // Each rank takes an equal contiguous piece of the one-process arrays, whatever the number
    // of ranks that wrote them; the next rebuild moves the particles to their cells' owners.
    ranks_->balance(r.positions);
    const auto [b, e] = ranks_->share(n_);
    auto piece = [b = b, e = e](const auto& v) {
      using V = std::decay_t<decltype(v)>;
      return V(v.begin() + std::ptrdiff_t(b), v.begin() + std::ptrdiff_t(e));
    };
    backend_.upload(pos_, piece(r.positions));
    backend_.upload(vel_, piece(r.velocities));
    backend_.upload(accel_, piece(r.accel));
    backend_.upload(ids_, piece(r.ids));
    backend_.upload(density_, piece(r.density));
    backend_.upload(pressure_, piece(r.pressure));
    if (dfsph()) {
      backend_.upload(kappa_density_, piece(r.kappa_density));
      backend_.upload(kappa_divergence_, piece(r.kappa_divergence));
    }
    ranks_->restore({uint32_t(e - b), 0, uint32_t(e - b)});
    // The open block's stats are maxima, except the outside count, a sum: rank 0 keeps it.
    if (!block_stats.empty() && ranks_->rank() != 0) block_stats[kSphStatOutside] = 0;
  } else {
    backend_.upload(pos_, r.positions);
    backend_.upload(vel_, r.velocities);
    backend_.upload(accel_, r.accel);
    backend_.upload(ids_, r.ids);
    backend_.upload(density_, r.density);
    backend_.upload(pressure_, r.pressure);
    if (dfsph()) {
      backend_.upload(kappa_density_, r.kappa_density);
      backend_.upload(kappa_divergence_, r.kappa_divergence);
    }
  }
  time_ = r.time;
  last_dt_ = r.last_dt;
  adaptive_dt_ = r.adaptive_dt;
  steps_ = r.steps;
  substeps_ = r.substeps;
  retries_ = r.retries;
  block_replays_ = r.block_replays;
  stats_ = r.stats;
  lag_stats_ = r.lag_stats;
  solve_stats_ = r.solve_stats;
  accel_valid_ = r.accel_valid;
  fields_current_ = r.fields_current;
  kappa_warm_ = r.kappa_warm;
  block_steps_ = r.block_steps;
  block_open_ = !r.block_stats.empty();
  block_limit_ = r.block_limit;
  if (block_open_) backend_.upload(stats_buf_, block_stats);
  watchdog_ = r.watchdog;
  next_energy_check_ = r.next_energy_check;
  good_ = {r.good_positions, r.good_velocities, r.good_time, r.good_last_dt,
           r.good_steps,     r.good_substeps,   r.good_stats};
  if (dfsph() && accel_valid_) {
    // A dfsph step starts from the grid, density, factor and neighbour rows at pos_, which the
    // step before left: rebuilt here (the kappa sums move with the particles; on several ranks
    // this rebuild brings the halos). The positions are in the cell order of that step's
    // rebuild, which the stable counting sort keeps, so the sums run in the same order.
    sort_state();
    dfsph_fields(pos_);
  }
}

}  // namespace masav
