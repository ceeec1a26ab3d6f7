#pragma once
// The SPH simulation's step control: chooses dt, records one step with the scene's scheme,
// reads its stats back and judges them (the CFL guard and the watchdog's bounds), commits or
// retries, and names what went wrong.
//
// CFL guard. dt is limited by C_v h / (c + v_max), C_f sqrt(h / a_max) and C_nu h^2 / nu (and
// the skin for RK4). Adaptive mode takes the smallest (growing at most 25% per step). A fixed dt
// over the limit is split into equal sub-steps (guard `reduce`) or stops with advice (`stop`).
// After every step the new velocities are checked: a step whose Courant number exceeded twice
// the limit, whose RK4 drift exceeded the skin, or that produced a NaN/Inf is rolled back and
// retried with half the dt; below dt_min the run stops with advice. A NaN that persists names the
// step and the particle. The last good state stays available (download()) after any error.
//
// The stability watchdog (sph_watchdog.h) stops a blown-up run whatever the guard's mode: its
// speed and density bounds are judged here with every step's stats, its energy check every
// SphWatchdog::kEnergyEvery steps (sph_energy_watch.h).
#include <cstdint>
#include <string>

#include "engine/core/error.h"
#include "engine/sph/sph_context.h"

namespace masav {

class SphEnergyWatch;
class SphScheme;
class SphStateReader;

class SphStepControl {
 public:
  SphStepControl(const SphContext& c, SphScheme& scheme, SphEnergyWatch& watch,
                 SphStateReader& reads)
      : c_(c), scheme_(scheme), watch_(watch), reads_(reads) {}

  static constexpr uint64_t kMaxSubsteps = 1u << 20;  // of one fixed-dt step (CFL guard)
  // Halvings of one step's dt the guard tries before it stops (a restored state's retry count
  // is bounded by it, sph_resume_checks.h).
  static constexpr int kMaxRetries = 12;

  // The limit the CFL conditions give for stats `s`, and for the current state's (s).
  double limit_for(const SphStepStats& s) const;
  double dt_limit() const;

  // What the stats of a step (or of a block of steps) say.
  struct Verdict {
    bool ok = true;
    bool overflow = false;  // neighbour candidates beyond max_candidates
    bool watchdog = false;  // beyond a watchdog bound: stop, do not retry
    std::string reason;
  };
  // Whether stats `w` / `s` of a step (or a block) of at most `dt` are acceptable.
  Verdict judge(const uint32_t w[kSphStatWords], const SphStepStats& s, double dt) const;

  // SphSimulation::step(): dt (fixed, possibly split into sub-steps by the CFL guard) or the
  // adaptive dt, each attempt's stats read back and judged. Throws masav::Error (state left at
  // the last good step).
  void step();
  // The scheme's kernels for one step of dt, and their commit (time and step counts with it),
  // without a read: what a block records.
  void record(double dt);
  void commit(double dt);
  // The watchdog's energy check where one is due at the current step.
  void watch_energy();

  // Throws e as an error of the simulation's own checks (SphSimulation::failed_together()).
  [[noreturn]] void fail_together(const Error& e);
  bool failed_together() const { return failed_together_; }
  uint64_t retries() const { return retries_; }  // steps the guard rejected and retried
  void set_retries(uint64_t retries) { retries_ = retries; }

 private:
  double courant_scale() const;  // the integrator's share of the Courant number
  Verdict attempt(double dt);    // one integrator step, committed if accepted
  // attempt() with the guard's retries at half the step; `whole` covers all of dt.
  void advance(double dt, int depth, bool whole);
  [[noreturn]] void fail_non_finite(double dt);
  [[noreturn]] void fail_non_finite_ranks(double dt);
  // The error naming particle `id` (UINT32_MAX: unknown) that entered the step non-finite
  // (`origin`) or got so in it.
  [[noreturn]] void throw_non_finite(double dt, uint32_t id, bool origin);

  SphContext c_;
  SphScheme& scheme_;
  SphEnergyWatch& watch_;
  SphStateReader& reads_;
  uint64_t retries_ = 0;
  bool failed_together_ = false;
};

}  // namespace masav
