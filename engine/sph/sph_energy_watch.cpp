// SphEnergyWatch: the watchdog's baseline, its energy check every SphWatchdog::kEnergyEvery
// steps and the return to the last good state when the check fails.
#include "engine/sph/sph_energy_watch.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "engine/sph/sph_device_state.h"
#include "engine/sph/sph_ranks.h"

namespace masav {

void SphEnergyWatch::start(const SphState& s0, double max_density) {
  bounds_ = make_watchdog(s0, sim_, max_density);
  set_baseline(s0);
}

void SphEnergyWatch::set_baseline(const SphState& s) {
  const SphProgress& p = c_.progress;
  bounds_.energy0 = available_energy(s, sim_);
  good_ = {s.positions, s.velocities, p.time, p.last_dt, p.steps, p.substeps, p.stats};
  c_.progress.next_energy_check = p.steps + SphWatchdog::kEnergyEvery;
}

std::optional<Error> SphEnergyWatch::check(const SphState& s, SphProgress at) {
  const double e = available_energy(s, sim_);
  // Half the fluid's mass at 5% of c0: the scale below which a rise is noise.
  const double c = c_.scene.sound_speed;
  const double floor = 0.5 * c_.layout.mass * double(c_.layout.fluid) * 0.0025 * c * c;
  const double bound =
      bounds_.energy0 + SphWatchdog::kEnergyMargin * std::max(std::abs(bounds_.energy0), floor);
  SphProgress& p = c_.progress;
  if (e <= bound) {
    good_ = {s.positions, s.velocities, at.time, at.last_dt, at.steps, at.substeps, at.stats};
    p.next_energy_check = at.steps + SphWatchdog::kEnergyEvery;
    return std::nullopt;
  }
  const uint64_t bad_step = at.steps;
  const double bad_time = at.time;
  // Back to the last state that passed: positions and velocities by id, in id order.
  SphDeviceState& d = c_.device;
  if (c_.ranks) {
    c_.ranks->scatter_by_id(good_.positions, good_.velocities, false, d.pos, d.vel, d.ids);
  } else {
    std::vector<uint32_t> ids(c_.n());
    for (uint32_t i = 0; i < c_.n(); ++i) ids[i] = i;
    c_.backend.upload(d.pos, good_.positions);
    c_.backend.upload(d.vel, good_.velocities);
    c_.backend.upload(d.ids, ids);
  }
  p.time = good_.time;
  p.last_dt = good_.last_dt;
  p.steps = good_.steps;
  p.substeps = good_.substeps;
  p.stats = good_.stats;
  p.lag_stats = p.stats;
  p.accel_valid = false;
  p.fields_current = false;
  return Error(c_.backend.name(), "sph watchdog",
               fmt::format("step {} (t = {:.6g} s): the energy above the floor reached {:.4g} J, "
                           "above the watchdog's bound {:.4g} J (the initial {:.4g} J plus "
                           "{:.0f}%); the state is back at step {} (t = {:.6g} s), the last that "
                           "passed",
                           bad_step, bad_time, e, bound, bounds_.energy0,
                           100 * SphWatchdog::kEnergyMargin, p.steps, p.time),
               watchdog_remedy());
}

}  // namespace masav
