// SphStepControl: the dt limit and the CFL guard, one step's attempt with its read and judge,
// the retries at half the step, and the errors naming the step, the particle and the remedy.
#include "engine/sph/sph_step_control.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>

#include "engine/kernels/kernel_checks.h"
#include "engine/sph/sph_coefficients.h"
#include "engine/sph/sph_device_state.h"
#include "engine/sph/sph_energy_watch.h"
#include "engine/sph/sph_field_evaluator.h"
#include "engine/sph/sph_ranks.h"
#include "engine/sph/sph_scheme.h"
#include "engine/sph/sph_state_reads.h"

namespace masav {
namespace {

bool finite_state(const Vec4d& p, const Vec4d& v) {
  return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z) && std::isfinite(v.x) &&
         std::isfinite(v.y) && std::isfinite(v.z);
}

}  // namespace

// Forward Euler multiplies the energy of every undamped oscillation by 1 + (omega dt)^2 per
// step, and a fluid's sound waves are such oscillations: at the others' Courant number a dam
// break doubles its energy within 400 steps (512 particles), at half of it still gains 27%, at
// a quarter it loses energy as the viscosity and walls take it. So Euler steps are 4x shorter.
// dfsph has no speed of sound in its limit, only the flow's: its Courant number is halved, to
// dt = 0.1 h / v_max = 0.2 dx / v_max at h = 2 dx (SPlisHSPlasH's default). The solves then
// take fewer iterations per step, and the density the particles reach stays closer to what the
// density solve predicted (dam break, 4,096 particles: mean compression 0.03% rather than 0.1%,
// about the same iterations per simulated second).
double SphStepControl::courant_scale() const {
  if (c_.dfsph()) return 0.5;
  return c_.scene.integrator == SphIntegrator::euler ? 0.25 : 1.0;
}

double SphStepControl::limit_for(const SphStepStats& s) const {
  const double h = c_.layout.h;
  const double c = signal_speed(c_.fields.params());
  const double k = courant_scale();
  double dt = k * c_.scene.cfl_velocity * h / (c + s.max_speed);
  if (s.max_accel > 0) dt = std::min(dt, k * c_.scene.cfl_force * std::sqrt(h / s.max_accel));
  if (c_.scene.viscosity > 0) dt = std::min(dt, c_.scene.cfl_viscous * h * h / c_.scene.viscosity);
  if (c_.fields.skin() > 0 && s.max_speed > 0)
    dt = std::min(dt, 0.5 * 0.5 * c_.fields.skin() / s.max_speed);
  return dt;
}

double SphStepControl::dt_limit() const {
  return limit_for(c_.progress.stats);
}

void SphStepControl::record(double dt) {
  scheme_.record(dt);
  c_.progress.fields_current = false;
}

SphStepControl::Verdict SphStepControl::judge(const uint32_t w[kSphStatWords],
                                              const SphStepStats& s, double dt) const {
  Verdict a;
  if (w[kSphStatOverflow] != 0) {
    a.ok = false;
    a.overflow = true;
    a.reason = "neighbour candidates overflowed";
  } else if (w[kSphStatNonFinite] != 0) {
    a.ok = false;
    a.reason = "a position or velocity became NaN/Inf";
  } else if (c_.fields.skin() > 0 && s.max_drift > 0.5 * c_.fields.skin()) {
    a.ok = false;
    a.reason = fmt::format(
        "an RK4 stage moved a particle {:.3g} m, more than the grid's skin / 2 "
        "= {:.3g} m",
        s.max_drift, 0.5 * c_.fields.skin());
  } else if (c_.scene.cfl_guard != SphCflGuard::off) {
    const double courant = dt * (signal_speed(c_.fields.params()) + s.max_speed) / c_.layout.h;
    if (courant > 2.0 * courant_scale() * c_.scene.cfl_velocity) {
      a.ok = false;
      a.reason = fmt::format(
          "the Courant number reached {:.3g} (limit {:.3g}: max speed {:.3g} "
          "m/s)",
          courant, courant_scale() * c_.scene.cfl_velocity, s.max_speed);
    }
  }
  if (!a.ok) return a;
  if (s.max_speed > watch_.bounds().max_speed) {
    a.ok = false;
    a.watchdog = true;
    a.reason = fmt::format(
        "a particle reached {:.3g} m/s, above the watchdog's speed bound {:.3g} m/s (2x the "
        "largest of the speed of sound c0, the free-fall speed over the box and the initial "
        "speeds)",
        s.max_speed, watch_.bounds().max_speed);
  } else if (s.max_density > watch_.bounds().max_density) {
    a.ok = false;
    a.watchdog = true;
    a.reason = fmt::format(
        "the density reached {:.4g} kg/m^3, above the watchdog's bound {:.4g} kg/m^3 (2x the "
        "rest or initial density; 3x for the thesis model)",
        s.max_density, watch_.bounds().max_density);
  } else if (s.max_speed * dt > c_.layout.h) {
    // Past h in one step a particle can pass a neighbour it never saw: the pair's force, which
    // every pressure model relies on to keep particles apart, is skipped and the energy budget
    // no longer says anything (the thesis gas's unbounded expansion energy hides the gain).
    a.ok = false;
    a.watchdog = true;
    a.reason = fmt::format(
        "a particle at {:.3g} m/s moved up to {:.3g} m in a step, more than the support radius "
        "h = {:.3g} m (its neighbours' forces are skipped)",
        s.max_speed, s.max_speed * dt, c_.layout.h);
  }
  return a;
}

void SphStepControl::commit(double dt) {
  scheme_.commit();
  c_.progress.time += dt;
  c_.progress.last_dt = dt;
  ++c_.progress.substeps;
}

SphStepControl::Verdict SphStepControl::attempt(double dt) {
  SphFieldEvaluator& f = c_.fields;
  f.start_stage_times();
  f.clear_stats();
  record(dt);
  uint32_t w[kSphStatWords];
  const SphStepStats s = f.read_stats(w);  // waits for the step
  f.collect_stage_times();
  const Verdict a = judge(w, s, dt);
  if (a.overflow)
    fail_together(
        Error(c_.backend.name(), "sph",
              fmt::format("step {}: a particle has more than {} neighbour candidates in its 27 "
                          "cells (the fluid is compressed far beyond rest density)",
                          c_.progress.steps + 1, c_.scene.max_candidates),
              fmt::format("raise max_candidates (at most {}), lower dt, or stiffen the fluid "
                          "(sound_speed, kp)",
                          max_sph_candidates(kPortableLoopBudget))));
  if (a.watchdog)
    fail_together(Error(c_.backend.name(), "sph watchdog",
                        fmt::format("step {} (t = {:.6g} s, dt = {:.3g} s): {}",
                                    c_.progress.steps + 1, c_.progress.time, dt, a.reason),
                        watchdog_remedy()));
  if (!a.ok) {
    if (c_.ends_rebuilt()) c_.progress.accel_valid = false;
    return a;
  }
  commit(dt);
  c_.progress.stats = s;
  return a;
}

void SphStepControl::fail_non_finite(double dt) {
  if (c_.ranks) fail_non_finite_ranks(dt);
  const SphDeviceState& d = c_.device;
  // Name the particle: one already non-finite in the committed state (the origin), else the
  // first one the step turned non-finite.
  auto first_bad = [](const std::vector<Vec4d>& p, const std::vector<Vec4d>& v,
                      const std::vector<uint32_t>& ids) {
    uint32_t best = UINT32_MAX;
    for (size_t i = 0; i < p.size(); ++i) {
      const bool bad = !std::isfinite(p[i].x) || !std::isfinite(p[i].y) || !std::isfinite(p[i].z) ||
                       !std::isfinite(v[i].x) || !std::isfinite(v[i].y) || !std::isfinite(v[i].z);
      if (bad) best = std::min(best, ids[i]);
    }
    return best;
  };
  uint32_t id =
      first_bad(c_.backend.download(d.pos), c_.backend.download(d.vel), c_.backend.download(d.ids));
  const bool origin = id != UINT32_MAX;
  if (!origin) {
    const bool lf = c_.ends_rebuilt();
    id = first_bad(c_.backend.download(lf ? d.ta : d.xs), c_.backend.download(lf ? d.tb : d.vs),
                   c_.backend.download(lf ? d.ids_t : d.ids));
  }
  throw_non_finite(dt, id, origin);
}

void SphStepControl::fail_together(const Error& e) {
  failed_together_ = true;
  throw e;
}

void SphStepControl::throw_non_finite(double dt, uint32_t id, bool origin) {
  fail_together(
      Error(c_.backend.name(), "sph",
            fmt::format("step {} (t = {:.6g} s, dt = {:.3g} s): particle {} {} a non-finite "
                        "position or velocity",
                        c_.progress.steps + 1, c_.progress.time, dt,
                        id == UINT32_MAX ? std::string("?") : std::to_string(id),
                        origin ? "entered the step with" : "got"),
            "the state of the last good step is kept (export it to inspect); lower dt or use "
            "the adaptive dt, raise viscosity, or check the scene's parameters"));
}

void SphStepControl::advance(double dt, int depth, bool whole) {
  const Verdict a = attempt(dt);
  if (a.ok) return;
  ++retries_;
  const bool non_finite = a.reason.find("NaN") != std::string::npos;
  if (c_.scene.cfl_guard == SphCflGuard::stop || c_.scene.cfl_guard == SphCflGuard::off ||
      depth >= kMaxRetries || dt * 0.5 < c_.scene.dt_min) {
    if (non_finite) fail_non_finite(dt);
    fail_together(
        Error(c_.backend.name(), "sph cfl guard",
              fmt::format("step {} (t = {:.6g} s) with dt = {:.3g} s was unstable: {}",
                          c_.progress.steps + 1, c_.progress.time, dt, a.reason),
              c_.scene.cfl_guard == SphCflGuard::stop
                  ? fmt::format("use dt <= {:.3g} s (the CFL limit now) or the adaptive dt, "
                                "or --cfl-guard reduce to let masav split steps",
                                dt_limit())
                  : fmt::format("the guard could not stabilise it above dt_min = {:.3g} s: "
                                "lower sound_speed or kp, raise viscosity, or give the fluid "
                                "more room",
                                c_.scene.dt_min)));
  }
  // Retry with half the step; a fixed-dt step still covers its whole interval.
  advance(0.5 * dt, depth + 1, whole);
  if (whole) advance(0.5 * dt, depth + 1, whole);
}

void SphStepControl::step() {
  c_.progress.block_open =
      false;  // a step of its own ends run()'s block (its stats are reset below)
  const double limit = dt_limit();
  if (c_.scene.dt) {
    const double dt = *c_.scene.dt;
    uint64_t parts = 1;
    if (dt > limit && c_.scene.cfl_guard != SphCflGuard::off) {
      if (c_.scene.cfl_guard == SphCflGuard::stop)
        fail_together(Error(
            c_.backend.name(), "sph cfl guard",
            fmt::format("step {} (t = {:.6g} s): dt = {:.3g} s exceeds the CFL limit "
                        "{:.3g} s (velocity {:.3g} m/s, acceleration {:.3g} m/s^2, "
                        "signal speed {:.3g} m/s, h = {:.3g} m)",
                        c_.progress.steps + 1, c_.progress.time, dt, limit,
                        c_.progress.stats.max_speed, c_.progress.stats.max_accel,
                        signal_speed(c_.fields.params()), c_.layout.h),
            fmt::format("use dt <= {:.3g} s, the adaptive dt, or --cfl-guard reduce", limit)));
      const double want = std::ceil(dt / limit);
      if (want > double(kMaxSubsteps) || dt / want < c_.scene.dt_min)
        fail_together(
            Error(c_.backend.name(), "sph cfl guard",
                  fmt::format("step {}: dt = {:.3g} s would need {:.3g} sub-steps of the CFL "
                              "limit {:.3g} s",
                              c_.progress.steps + 1, dt, want, limit),
                  "use a smaller dt or the adaptive dt; lower sound_speed or kp"));
      parts = uint64_t(want);
    }
    for (uint64_t k = 0; k < parts; ++k) advance(dt / double(parts), 0, true);
  } else {
    const double dt = std::min({limit, c_.progress.adaptive_dt * 1.25, c_.scene.dt_max});
    if (dt < c_.scene.dt_min)
      fail_together(
          Error(c_.backend.name(), "sph cfl guard",
                fmt::format("step {} (t = {:.6g} s): the CFL limit {:.3g} s is below dt_min = "
                            "{:.3g} s (max speed {:.3g} m/s, max acceleration {:.3g} m/s^2)",
                            c_.progress.steps + 1, c_.progress.time, dt, c_.scene.dt_min,
                            c_.progress.stats.max_speed, c_.progress.stats.max_accel),
                "the fluid is blowing up: lower sound_speed or kp, raise viscosity"));
    advance(dt, 0, false);
    c_.progress.adaptive_dt = c_.progress.last_dt;
  }
  ++c_.progress.steps;
  c_.progress.lag_stats =
      c_.progress.stats;  // a block after a step takes its limit from the step's stats
  watch_energy();
}

void SphStepControl::fail_non_finite_ranks(double dt) {
  // As fail_non_finite: the smallest id non-finite in the committed state (the origin), else the
  // smallest the step made non-finite, over every rank's own particles.
  const SphDeviceState& d = c_.device;
  auto first_bad = [&](const Buffer<Real4>& p, const Buffer<Real4>& v, const Buffer<uint32_t>& id,
                       const SphRankLayout& l) {
    const auto pos = c_.backend.download(p);
    const auto vel = c_.backend.download(v);
    const auto ids = c_.backend.download(id);
    uint32_t best = UINT32_MAX;
    for (uint32_t i = l.first; i < l.first + l.own; ++i)
      if (!finite_state(pos[i], vel[i])) best = std::min(best, ids[i]);
    return c_.ranks->min(best);
  };
  uint32_t id = first_bad(d.pos, d.vel, d.ids, c_.ranks->committed());
  const bool origin = id != UINT32_MAX;
  if (!origin) {
    const bool lf = c_.ends_rebuilt();
    id = lf ? first_bad(d.ta, d.tb, d.ids_t, c_.ranks->staged())
            : first_bad(d.xs, d.vs, d.ids, c_.ranks->committed());
  }
  throw_non_finite(dt, id, origin);
}

void SphStepControl::watch_energy() {
  if (c_.progress.steps < c_.progress.next_energy_check) return;
  if (std::optional<Error> e = watch_.check(reads_.download(), c_.progress)) fail_together(*e);
}

}  // namespace masav
