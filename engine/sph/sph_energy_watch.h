#pragma once
// The watchdog's energy check of a running simulation (sph_watchdog.h): every
// SphWatchdog::kEnergyEvery steps the energy of a downloaded state against the baseline; beyond
// the bound the state goes back to the last that passed and the run stops with the watchdog's
// message. Holds the watchdog's bounds (which the step control's judge also reads) and that
// last good state.
#include <optional>
#include <vector>

#include "engine/core/error.h"
#include "engine/sph/sph_context.h"
#include "engine/sph/sph_watchdog.h"

namespace masav {

class SphSimulation;

// The last state that passed the energy check, by particle id, and the host state it had.
struct SphGoodState {
  std::vector<Vec4d> positions, velocities;
  double time = 0, last_dt = 0;
  uint64_t steps = 0, substeps = 0;
  SphStepStats stats;
};

class SphEnergyWatch {
 public:
  // `sim`: the simulation whose energy it measures (available_energy reads its scene).
  SphEnergyWatch(const SphContext& c, const SphSimulation& sim) : c_(c), sim_(sim) {}

  // The bounds for a run starting from `s0`; then `s0` is the baseline.
  void start(const SphState& s0, double max_density);
  // `s`, at the current host state, is the new baseline: its energy, the last good state, the
  // next check's step.
  void set_baseline(const SphState& s);
  // The check of state `s`, taken at host state `at` (the current one, or a pending block's
  // end): passes (the last good state, the next check's step), or restores the last good state
  // and returns the error to throw.
  std::optional<Error> check(const SphState& s, SphProgress at);

  SphWatchdog& bounds() { return bounds_; }
  const SphWatchdog& bounds() const { return bounds_; }
  SphGoodState& good() { return good_; }
  const SphGoodState& good() const { return good_; }

 private:
  SphContext c_;
  const SphSimulation& sim_;
  SphWatchdog bounds_;
  SphGoodState good_;
};

}  // namespace masav
