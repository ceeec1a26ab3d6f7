// validate_resume_state: each field of a restored SPH state against the scene's bounds (the ones
// validate() and the step control use) and against the fields it must agree with.
#include "engine/sph/sph_resume_checks.h"

#include <fmt/format.h>

#include <bit>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "engine/core/error.h"
#include "engine/kernels/sph_kernel_params.h"
#include "engine/sph/sph_block_scheduler.h"
#include "engine/sph/sph_particles.h"
#include "engine/sph/sph_step_control.h"

namespace masav {
namespace {

constexpr const char* kWhere = "sph resume state";
// The counters are used as doubles (rates, the CSV, time bounds): past 2^53 they are not exact.
constexpr uint64_t kMaxCount = uint64_t(1) << 53;

[[noreturn]] void bad(std::string_view field, const std::string& value,
                      const std::string& allowed) {
  throw_invalid(kWhere, field, value, allowed);
}

std::string num(double v) {
  return fmt::format("{}", v);
}

void finite_in(std::string_view field, double v, double lo, double hi, const char* unit) {
  if (!std::isfinite(v) || v < lo || v > hi)
    bad(field, num(v), fmt::format("finite and in [{}, {}] {}", lo, hi, unit));
}

void count_at_most(std::string_view field, uint64_t v, uint64_t most, const std::string& why) {
  if (v > most) bad(field, std::to_string(v), fmt::format("at most {} ({})", most, why));
}

template <class T>
void length(std::string_view field, const std::vector<T>& v, size_t want, const std::string& why) {
  if (v.size() != want)
    bad(field, fmt::format("{} values", v.size()), fmt::format("{} values ({})", want, why));
}

bool finite3(const Vec4d& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}
std::string vec(const Vec4d& v) {
  return fmt::format("({}, {}, {})", v.x, v.y, v.z);
}
std::string vec(const Vec3d& v) {
  return fmt::format("({}, {}, {})", v.x, v.y, v.z);
}

// The dt of one committed integrator step: the step control never goes below the lower bound
// (a retry stops before halving under dt_min, a split fixed dt likewise, unless the fixed dt
// itself is smaller) nor above the fixed dt or the adaptive ceiling dt_max.
struct DtBounds {
  double lo, hi;
};
DtBounds dt_bounds(const SphScene& s) {
  if (s.dt) return {std::min(*s.dt, s.dt_min), *s.dt};
  return {s.dt_min, s.dt_max};
}

void check_dt(std::string_view field, double dt, uint64_t substeps, const DtBounds& b) {
  if (substeps == 0) {
    if (dt != 0) bad(field, num(dt), "0 before the first integrator step (substeps = 0)");
    return;
  }
  finite_in(field, dt, b.lo, b.hi, "s (the scene's dt bounds)");
}

// Time is the sum of the committed steps' dt: 0 before any, at most substeps x the largest dt
// (plus the sum's rounding).
void check_time(std::string_view field, double t, uint64_t substeps, const DtBounds& b) {
  const double n = double(substeps);
  const double most = n * b.hi * (1 + 1e-9 + n * std::numeric_limits<double>::epsilon());
  if (!std::isfinite(t) || t < 0 || t > most || (substeps == 0) != (t == 0))
    bad(field, num(t),
        substeps == 0 ? std::string("0 s before the first integrator step (substeps = 0)")
                      : fmt::format("finite and in (0, {}] s ({} integrator steps of at most {} s)",
                                    most, substeps, b.hi));
}

void check_stats(std::string_view field, const SphStepStats& s, const SphScene& scene) {
  const std::string f(field);
  finite_in(f + ".max_speed", s.max_speed, 0, std::numeric_limits<double>::max(), "m/s");
  finite_in(f + ".max_accel", s.max_accel, 0, std::numeric_limits<double>::max(), "m/s^2");
  finite_in(f + ".max_drift", s.max_drift, 0, std::numeric_limits<double>::max(), "m");
  finite_in(f + ".max_density", s.max_density, 0, std::numeric_limits<double>::max(), "kg/m^3");
  // A step whose candidates overflowed is never committed, so no kept read exceeds the bound.
  count_at_most(f + ".max_candidates", s.max_candidates, scene.max_candidates,
                "the scene's max_candidates");
  count_at_most(f + ".max_neighbors", s.max_neighbors, scene.max_candidates,
                "the scene's max_candidates: neighbours are candidates");
}

// The particles: finite, inside the box (walls on), each id's inverse mass the scene's.
void check_positions(std::string_view field, const std::vector<Vec4d>& p,
                     const std::vector<uint32_t>* ids, const SphScene& s, const SphSpacing& sp) {
  const double slack = kResumeBoxSlackH * sp.h;
  const Vec3d lo{s.box_min.x - slack, s.box_min.y - slack, s.box_min.z - slack};
  const Vec3d hi{s.box_max.x + slack, s.box_max.y + slack, s.box_max.z + slack};
  const double obstacle_w =
      !s.obstacle.enabled || s.obstacle.pinned ? 0.0 : 1.0 / s.obstacle.mass_ratio;
  for (size_t i = 0; i < p.size(); ++i) {
    const Vec4d& x = p[i];
    const std::string at = fmt::format("{}[{}]", field, i);
    if (!finite3(x)) bad(at, vec(x), "finite in every component (m)");
    if (s.walls &&
        (x.x < lo.x || x.y < lo.y || x.z < lo.z || x.x > hi.x || x.y > hi.y || x.z > hi.z))
      bad(at, vec(x),
          fmt::format("inside the box {} .. {} within {} h = {} m (walls on)", vec(s.box_min),
                      vec(s.box_max), kResumeBoxSlackH, slack));
    if (!ids) continue;
    // w: the inverse mass scale build_particles gave the particle (a backend's floats round it).
    const uint32_t id = (*ids)[i];
    const double want = id < sp.fluid ? 1.0 : obstacle_w;
    if (!(std::abs(x.w - want) <= 1e-6 * want))
      bad(at + ".w", num(x.w),
          fmt::format("{} (the inverse mass scale of particle {}, {})", want, id,
                      id < sp.fluid ? "fluid" : "obstacle"));
  }
}

void check_finite(std::string_view field, const std::vector<Vec4d>& v, const char* unit) {
  for (size_t i = 0; i < v.size(); ++i)
    if (!finite3(v[i]))
      bad(fmt::format("{}[{}]", field, i), vec(v[i]),
          fmt::format("finite in every component ({})", unit));
}

void check_finite(std::string_view field, const std::vector<double>& v, double lo,
                  const char* unit) {
  for (size_t i = 0; i < v.size(); ++i)
    if (!std::isfinite(v[i]) || v[i] < lo)
      bad(fmt::format("{}[{}]", field, i), num(v[i]),
          lo == -std::numeric_limits<double>::infinity()
              ? fmt::format("finite ({})", unit)
              : fmt::format("finite and >= {} ({})", lo, unit));
}

void check_ids(const std::vector<uint32_t>& ids) {
  const size_t n = ids.size();
  std::vector<bool> seen(n, false);
  for (size_t i = 0; i < n; ++i) {
    const uint32_t id = ids[i];
    if (id >= n || seen[id])
      bad(fmt::format("ids[{}]", i), std::to_string(id),
          fmt::format("each of 0 to {} exactly once ({})", n - 1,
                      id >= n ? "out of range" : "a duplicate"));
    seen[id] = true;
  }
}

// An open block's stats words (kSphStatWords): the float words hold non-negative floats' bits
// (their maxima are taken as unsigned integers), never a NaN.
void check_block(const SphResumeState& r) {
  if (r.block_stats.empty()) return;
  length("block_stats", r.block_stats, kSphStatWords, "kSphStatWords, for an open block");
  if (std::isnan(r.block_limit) || !(r.block_limit > 0))
    bad("block_limit", num(r.block_limit), "a dt limit > 0 s (+inf where no CFL condition binds)");
  for (const uint32_t word :
       {kSphStatMaxSpeed2, kSphStatMaxAccel2, kSphStatMaxDisp2, kSphStatMaxDensity}) {
    const float f = std::bit_cast<float>(r.block_stats[word]);
    if (std::isnan(f) || std::signbit(f))
      bad(fmt::format("block_stats[{}]", word), num(f), "a float >= 0 (a maximum so far)");
  }
}

void check_solves(const SphResumeState& r, const SphScene& s) {
  const SphSolveStats& ss = r.solve_stats;
  const bool dfsph = s.model == SphPressureModel::dfsph;
  if (!dfsph) {
    // Only dfsph solves: every other model exports zeros.
    if (ss.steps || ss.density_iterations || ss.divergence_iterations || ss.unconverged ||
        ss.last_density_error != 0 || ss.last_divergence_error != 0)
      bad("solve_stats", fmt::format("{} solved steps", ss.steps),
          fmt::format("all 0 for pressure model {} (only dfsph solves)", to_string(s.model)));
    if (r.kappa_warm)
      bad("kappa_warm", "1", fmt::format("0 for pressure model {}", to_string(s.model)));
    return;
  }
  const double most = double(ss.steps) * s.dfsph_max_iterations;
  const auto iterations = [&](const char* field, uint64_t v) {
    if (double(v) > most)
      bad(field, std::to_string(v),
          fmt::format("at most {} ({} solved steps x dfsph_max_iterations {})", most, ss.steps,
                      s.dfsph_max_iterations));
  };
  count_at_most("solve_stats.steps", ss.steps, kMaxCount, "a double's exact integers");
  iterations("solve_stats.density_iterations", ss.density_iterations);
  iterations("solve_stats.divergence_iterations", ss.divergence_iterations);
  count_at_most("solve_stats.unconverged", ss.unconverged, 2 * ss.steps,
                "two solves per solved step");
  finite_in("solve_stats.last_density_error", ss.last_density_error, 0,
            std::numeric_limits<double>::max(), "(relative)");
  finite_in("solve_stats.last_divergence_error", ss.last_divergence_error, 0,
            std::numeric_limits<double>::max(), "(relative)");
}

}  // namespace

void validate_resume_state(const SphScene& s, const SphResumeState& r) {
  validate(s);
  const SphSpacing sp = sph_spacing(s);
  const size_t n = sp.total();
  const std::string per = fmt::format("one per particle of the scene: {} fluid + {} obstacle",
                                      sp.fluid, sp.obstacle_count());
  const bool dfsph = s.model == SphPressureModel::dfsph;
  length("positions", r.positions, n, per);
  length("velocities", r.velocities, n, per);
  length("accelerations", r.accel, n, per);
  length("ids", r.ids, n, per);
  length("density", r.density, n, per);
  length("pressure", r.pressure, n, per);
  length("dfsph density kappa sums", r.kappa_density, dfsph ? n : 0,
         dfsph ? per : "none without pressure dfsph");
  length("dfsph divergence kappa sums", r.kappa_divergence, dfsph ? n : 0,
         dfsph ? per : "none without pressure dfsph");
  length("watchdog positions", r.good_positions, n, per);
  length("watchdog velocities", r.good_velocities, n, per);

  // The counters: substeps count every committed integrator step (a step has at least one, a
  // fixed dt at most kMaxSubsteps, each halved up to kMaxRetries times; a failed step may have
  // committed some of its own).
  count_at_most("steps", r.steps, kMaxCount, "a double's exact integers");
  if (r.substeps < r.steps)
    bad("substeps", std::to_string(r.substeps),
        fmt::format("at least steps = {} (every step commits one or more)", r.steps));
  const double most_substeps = double(r.steps + 1) * double(SphStepControl::kMaxSubsteps) *
                               std::ldexp(1.0, SphStepControl::kMaxRetries);
  if (double(r.substeps) > most_substeps || r.substeps > kMaxCount)
    bad("substeps", std::to_string(r.substeps),
        fmt::format("at most {} ((steps + 1) x kMaxSubsteps x 2^kMaxRetries, and 2^53)",
                    std::min(most_substeps, double(kMaxCount))));
  // Each retry halves a step that then commits or stops the run; each replay re-runs a block
  // step by step, which commits a step or stops the run.
  const double most_retries = double(SphStepControl::kMaxRetries) * double(r.substeps + 1);
  if (double(r.retries) > most_retries)
    bad("retries", std::to_string(r.retries),
        fmt::format("at most {} (kMaxRetries x (substeps + 1))", most_retries));
  count_at_most("block_replays", r.block_replays, r.steps + 1,
                "steps + 1: a replayed block commits a step or stops the run");

  const DtBounds b = dt_bounds(s);
  check_time("time", r.time, r.substeps, b);
  check_dt("last_dt", r.last_dt, r.substeps, b);
  finite_in("adaptive_dt", r.adaptive_dt, std::numeric_limits<double>::min(), s.dt_max,
            "s (> 0, at most the scene's dt_max)");
  check_stats("stats", r.stats, s);
  check_stats("lag_stats", r.lag_stats, s);
  check_solves(r, s);
  if (r.block_steps < 1 || r.block_steps > SphBlockScheduler::kMaxBlockSteps)
    bad("block_steps", std::to_string(r.block_steps),
        fmt::format("in [1, {}] (--block-steps)", SphBlockScheduler::kMaxBlockSteps));
  check_block(r);

  // The watchdog's bounds and its last good state, which the run may go back to: an earlier
  // state of the same run.
  finite_in("watchdog.max_speed", r.watchdog.max_speed, 0, std::numeric_limits<double>::max(),
            "m/s");
  finite_in("watchdog.max_density", r.watchdog.max_density, 0, std::numeric_limits<double>::max(),
            "kg/m^3");
  if (!std::isfinite(r.watchdog.energy0))
    bad("watchdog.energy0", num(r.watchdog.energy0), "finite (J)");
  count_at_most("good.steps", r.good_steps, r.steps, "steps: an earlier state");
  count_at_most("good.substeps", r.good_substeps, r.substeps, "substeps: an earlier state");
  if (r.good_substeps < r.good_steps)
    bad("good.substeps", std::to_string(r.good_substeps),
        fmt::format("at least good.steps = {}", r.good_steps));
  check_time("good.time", r.good_time, r.good_substeps, b);
  if (r.good_time > r.time)
    bad("good.time", num(r.good_time),
        fmt::format("at most time = {} s: an earlier state", r.time));
  check_dt("good.last_dt", r.good_last_dt, r.good_substeps, b);
  check_stats("good.stats", r.good_stats, s);
  // The next energy check is set one period past the last one that passed.
  if (r.next_energy_check < r.good_steps ||
      r.next_energy_check > r.steps + SphWatchdog::kEnergyEvery)
    bad("next_energy_check", std::to_string(r.next_energy_check),
        fmt::format("in [good.steps = {}, steps + {} = {}]", r.good_steps,
                    SphWatchdog::kEnergyEvery, r.steps + SphWatchdog::kEnergyEvery));

  // The particles.
  check_ids(r.ids);
  check_positions("positions", r.positions, &r.ids, s, sp);
  check_finite("velocities", r.velocities, "m/s");
  check_positions("watchdog positions", r.good_positions, nullptr, s, sp);
  check_finite("watchdog velocities", r.good_velocities, "m/s");
  if (r.accel_valid) check_finite("accelerations", r.accel, "m/s^2, carried: accel_valid");
  if (r.fields_current) {
    check_finite("density", r.density, 0, "kg/m^3, current: fields_current");
    check_finite("pressure", r.pressure, -std::numeric_limits<double>::infinity(),
                 "Pa, current: fields_current");
  }
  if (r.kappa_warm) {
    check_finite("dfsph density kappa sums", r.kappa_density,
                 -std::numeric_limits<double>::infinity(), "warm start: kappa_warm");
    check_finite("dfsph divergence kappa sums", r.kappa_divergence,
                 -std::numeric_limits<double>::infinity(), "warm start: kappa_warm");
  }
}

}  // namespace masav
