// SphSimulation's energy check (sph_watchdog.h): every SphWatchdog::kEnergyEvery steps the energy
// against the baseline; beyond the bound the state goes back to the last that passed and the run
// stops with the watchdog's message.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "engine/core/error.h"
#include "engine/sph/sph_simulation.h"

namespace masav {

void SphSimulation::set_watchdog_baseline(const SphState& s) {
  watchdog_.energy0 = available_energy(s, *this);
  good_ = {s.positions, s.velocities, time_, last_dt_, steps_, substeps_, stats_};
  next_energy_check_ = steps_ + SphWatchdog::kEnergyEvery;
}

void SphSimulation::watch_energy() {
  if (steps_ < next_energy_check_) return;
  check_energy(download(), save_host_state());
}

void SphSimulation::check_energy(const SphState& s, const HostState& at) {
  const double e = available_energy(s, *this);
  // Half the fluid's mass at 5% of c0: the scale below which a rise is noise.
  const double c = scene_.sound_speed;
  const double floor = 0.5 * layout_.mass * double(layout_.fluid) * 0.0025 * c * c;
  const double bound =
      watchdog_.energy0 + SphWatchdog::kEnergyMargin * std::max(std::abs(watchdog_.energy0), floor);
  if (e <= bound) {
    good_ = {s.positions, s.velocities, at.time, at.last_dt, at.steps, at.substeps, at.stats};
    next_energy_check_ = at.steps + SphWatchdog::kEnergyEvery;
    return;
  }
  const uint64_t bad_step = at.steps;
  const double bad_time = at.time;
  // Back to the last state that passed: positions and velocities by id, in id order.
  if (ranks_) {
    ranks_->scatter_by_id(good_.positions, good_.velocities, false, pos_, vel_, ids_);
  } else {
    std::vector<uint32_t> ids(n_);
    for (uint32_t i = 0; i < n_; ++i) ids[i] = i;
    backend_.upload(pos_, good_.positions);
    backend_.upload(vel_, good_.velocities);
    backend_.upload(ids_, ids);
  }
  time_ = good_.time;
  last_dt_ = good_.last_dt;
  steps_ = good_.steps;
  substeps_ = good_.substeps;
  stats_ = good_.stats;
  lag_stats_ = stats_;
  accel_valid_ = false;
  fields_current_ = false;
  fail_together(
      Error(backend_.name(), "sph watchdog",
            fmt::format("step {} (t = {:.6g} s): the energy above the floor reached {:.4g} J, "
                        "above the watchdog's bound {:.4g} J (the initial {:.4g} J plus {:.0f}%); "
                        "the state is back at step {} (t = {:.6g} s), the last that passed",
                        bad_step, bad_time, e, bound, watchdog_.energy0,
                        100 * SphWatchdog::kEnergyMargin, steps_, time_),
            watchdog_remedy()));
}

}  // namespace masav
