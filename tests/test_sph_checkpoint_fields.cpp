// Every field of a restored SPH state is checked like a flag or scene key (issue 45: a
// checkpoint was trusted once its checksums matched; a NaN time resumed a run that never
// advanced). Each case writes a valid checkpoint with one field corrupted -- through the
// writer, so every checksum is valid and only the field checks can refuse it -- and expects the
// read to throw masav::Error naming the field, and the same state handed to
// SphSimulation::restore_resume_state (the API's way in) to be refused too. Valid states of
// every scheme, mid-run and after the watchdog's energy checks, pass.
#include <doctest/doctest.h>
#include <fmt/format.h>

#include <bit>
#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "engine/sph/sph_resume_checks.h"
#include "tests/sph_checkpoint_fixture.h"
#include "tests/temp_dir.h"

using namespace masav;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

struct Corruption {
  const char* what;
  std::function<void(SphResumeState&)> apply;
  const char* message;  // a part of the read's message: the field (and its value)
};

bool has(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// Writes c's state corrupted by `k` and expects the read and the restore to refuse it.
void expect_refused(const test::CheckpointCase& c, const Corruption& k, const std::string& path) {
  const std::string what = k.what;
  CAPTURE(what);
  SphResumeState r = c.state;
  k.apply(r);
  write_sph_checkpoint(path, c.scene, r);
  const std::string e = test::checkpoint_read_error(path);
  CAPTURE(e);
  CHECK(has(e, path));
  CHECK(has(e, k.message));
  std::string restored;
  try {
    c.sim->restore_resume_state(r);
  } catch (const Error& err) {
    restored = err.what();
  }
  CAPTURE(restored);
  CHECK(has(restored, k.message));
}

SphScene water() {
  return make_preset("water", 300);
}

SphScene dfsph_scene() {
  SphScene s = make_preset("dam-break", 300);
  s.model = SphPressureModel::dfsph;
  s.integrator = SphIntegrator::symplectic_euler;
  return s;
}

}  // namespace

TEST_CASE("sph checkpoint fields: the issue's NaN and negative times are refused, naming time") {
  test::TempDir dir("sph_ckpt_time");
  const test::CheckpointCase c(water(), 20);
  const std::string path = dir.file("checkpoint.masav");
  write_sph_checkpoint(path, c.scene, c.state);
  REQUIRE(test::checkpoint_read_error(path).empty());
  expect_refused(c, {"NaN time", [](SphResumeState& r) { r.time = kNaN; }, "invalid time = nan"},
                 path);
  expect_refused(c, {"negative time", [](SphResumeState& r) { r.time = -1; }, "invalid time = -1"},
                 path);
  expect_refused(c, {"infinite time", [](SphResumeState& r) { r.time = kInf; }, "time = inf"},
                 path);
  // More than the steps taken can cover at the scene's largest dt.
  expect_refused(
      c, {"time beyond the steps", [](SphResumeState& r) { r.time = 1e3; }, "time = 1000"}, path);
}

TEST_CASE("sph checkpoint fields: each field of the state is checked, naming it") {
  test::TempDir dir("sph_ckpt_fields");
  const std::string path = dir.file("checkpoint.masav");
  const test::CheckpointCase c(water(), 20);
  REQUIRE(c.state.substeps >= 20);
  const std::vector<Corruption> cases = {
      {"dt NaN", [](SphResumeState& r) { r.last_dt = kNaN; }, "invalid last_dt = nan"},
      {"dt 0 after steps", [](SphResumeState& r) { r.last_dt = 0; }, "invalid last_dt = 0"},
      {"dt negative", [](SphResumeState& r) { r.last_dt = -1e-4; }, "invalid last_dt = -0.0001"},
      {"dt over dt_max", [](SphResumeState& r) { r.last_dt = 1; }, "the scene's dt bounds"},
      {"adaptive dt NaN", [](SphResumeState& r) { r.adaptive_dt = kNaN; }, "adaptive_dt = nan"},
      {"adaptive dt 0", [](SphResumeState& r) { r.adaptive_dt = 0; }, "adaptive_dt = 0"},
      {"steps absurd", [](SphResumeState& r) { r.steps = uint64_t(1) << 60; }, "invalid steps"},
      {"steps over substeps", [](SphResumeState& r) { r.steps = r.substeps + 1; },
       "invalid substeps"},
      {"substeps absurd", [](SphResumeState& r) { r.substeps = UINT64_MAX; }, "invalid substeps"},
      {"retries absurd", [](SphResumeState& r) { r.retries = UINT64_MAX; }, "invalid retries"},
      {"replays absurd", [](SphResumeState& r) { r.block_replays = r.steps + 2; },
       "invalid block_replays"},
      {"stats NaN", [](SphResumeState& r) { r.stats.max_speed = kNaN; }, "stats.max_speed = nan"},
      {"stats negative", [](SphResumeState& r) { r.lag_stats.max_accel = -1; },
       "lag_stats.max_accel = -1"},
      {"stats candidates", [](SphResumeState& r) { r.stats.max_candidates = 1u << 30; },
       "stats.max_candidates"},
      {"good stats", [](SphResumeState& r) { r.good_stats.max_density = kInf; },
       "good.stats.max_density = inf"},
      {"block steps 0", [](SphResumeState& r) { r.block_steps = 0; }, "invalid block_steps = 0"},
      {"block steps 65", [](SphResumeState& r) { r.block_steps = 65; }, "block_steps = 65"},
      {"open block NaN limit",
       [](SphResumeState& r) {
         r.block_limit = kNaN;
         r.block_stats.assign(kSphStatWords, 0);
       },
       "block_limit"},
      {"open block NaN speed",
       [](SphResumeState& r) {
         r.block_limit = 1e-3;
         r.block_stats.assign(kSphStatWords, 0);
         r.block_stats[kSphStatMaxSpeed2] = std::bit_cast<uint32_t>(std::nanf(""));
       },
       "block_stats[3] = nan"},
      {"watchdog speed", [](SphResumeState& r) { r.watchdog.max_speed = kNaN; },
       "watchdog.max_speed = nan"},
      {"watchdog density", [](SphResumeState& r) { r.watchdog.max_density = -1; },
       "watchdog.max_density = -1"},
      {"watchdog energy", [](SphResumeState& r) { r.watchdog.energy0 = kInf; },
       "watchdog.energy0 = inf"},
      {"next energy check", [](SphResumeState& r) { r.next_energy_check = UINT64_MAX; },
       "invalid next_energy_check"},
      {"good steps ahead", [](SphResumeState& r) { r.good_steps = r.steps + 1; },
       "invalid good.steps"},
      {"good time ahead", [](SphResumeState& r) { r.good_time = r.time + 1; }, "invalid good.time"},
      {"good time NaN", [](SphResumeState& r) { r.good_time = kNaN; }, "good.time = nan"},
      {"good dt", [](SphResumeState& r) { r.good_last_dt = kNaN; }, "good.last_dt"},
      {"position NaN", [](SphResumeState& r) { r.positions[5].y = kNaN; }, "positions[5] = "},
      {"position outside", [](SphResumeState& r) { r.positions[7].x = 3.5; }, "inside the box"},
      {"position mass", [](SphResumeState& r) { r.positions[9].w = 2; }, "positions[9].w = 2"},
      {"velocity inf", [](SphResumeState& r) { r.velocities[3].z = -kInf; }, "velocities[3] = "},
      {"ids duplicate", [](SphResumeState& r) { r.ids[1] = r.ids[0]; }, "a duplicate"},
      {"ids out of range", [](SphResumeState& r) { r.ids[2] = 300; }, "ids[2] = 300"},
      {"accelerations",
       [](SphResumeState& r) {
         r.accel_valid = true;
         r.accel[2].x = kNaN;
       },
       "accelerations[2] = "},
      {"density",
       [](SphResumeState& r) {
         r.fields_current = true;
         r.density[0] = kNaN;
       },
       "density[0] = nan"},
      {"pressure",
       [](SphResumeState& r) {
         r.fields_current = true;
         r.pressure[4] = kInf;
       },
       "pressure[4] = inf"},
      {"watchdog positions", [](SphResumeState& r) { r.good_positions[0].x = kNaN; },
       "watchdog positions[0] = "},
      {"watchdog velocities", [](SphResumeState& r) { r.good_velocities[1].x = kInf; },
       "watchdog velocities[1] = "},
      {"solve stats without dfsph", [](SphResumeState& r) { r.solve_stats.steps = 3; },
       "invalid solve_stats"},
      {"warm start without dfsph", [](SphResumeState& r) { r.kappa_warm = true; },
       "invalid kappa_warm"},
  };
  for (const Corruption& k : cases) expect_refused(c, k, path);
}

TEST_CASE("sph checkpoint fields: dfsph's solve counts and warm starts are checked") {
  test::TempDir dir("sph_ckpt_dfsph");
  const std::string path = dir.file("checkpoint.masav");
  const test::CheckpointCase c(dfsph_scene(), 6);
  REQUIRE(c.state.solve_stats.steps > 0);
  REQUIRE(c.state.kappa_warm);
  const std::vector<Corruption> cases = {
      {"density iterations", [](SphResumeState& r) { r.solve_stats.density_iterations = ~0ull; },
       "invalid solve_stats.density_iterations"},
      {"divergence iterations",
       [](SphResumeState& r) { r.solve_stats.divergence_iterations = ~0ull; },
       "invalid solve_stats.divergence_iterations"},
      {"unconverged", [](SphResumeState& r) { r.solve_stats.unconverged = ~0ull; },
       "invalid solve_stats.unconverged"},
      {"residual NaN", [](SphResumeState& r) { r.solve_stats.last_density_error = kNaN; },
       "solve_stats.last_density_error = nan"},
      {"kappa NaN", [](SphResumeState& r) { r.kappa_density[3] = kNaN; },
       "dfsph density kappa sums[3] = nan"},
      {"kappa inf", [](SphResumeState& r) { r.kappa_divergence[0] = kInf; },
       "dfsph divergence kappa sums[0] = inf"},
  };
  for (const Corruption& k : cases) expect_refused(c, k, path);
}

TEST_CASE(
    "sph checkpoint fields: the particle count, array lengths and preset agree with the scene") {
  test::TempDir dir("sph_ckpt_counts");
  const std::string path = dir.file("checkpoint.masav");
  const test::CheckpointCase c(water(), 5);
  SUBCASE("an obstacle particle fewer in every array: STAT.particles against the scene") {
    // The fluid count alone still fits: the obstacle's particles are part of the scene's count.
    const test::CheckpointCase o(make_preset("obstacle", 300), 2);
    const size_t n = o.state.positions.size();
    REQUIRE(n > 300);
    SphResumeState r = o.state;
    for (auto* v : {&r.positions, &r.velocities, &r.accel, &r.good_positions, &r.good_velocities})
      v->pop_back();
    r.density.pop_back();
    r.pressure.pop_back();
    r.ids.pop_back();
    write_sph_checkpoint(path, o.scene, r);
    const std::string e = test::checkpoint_read_error(path);
    CHECK(has(e, fmt::format("STAT.particles: {} where the scene has {}", n - 1, n)));
  }
  SUBCASE("one array short, through the API") {
    SphResumeState r = c.state;
    r.velocities.pop_back();
    CHECK_THROWS_WITH_AS(c.sim->restore_resume_state(r),
                         doctest::Contains("invalid velocities = 299 values"), Error);
    r = c.state;
    r.kappa_density.assign(300, 0.0);
    CHECK_THROWS_WITH_AS(c.sim->restore_resume_state(r),
                         doctest::Contains("dfsph density kappa sums = 300 values"), Error);
  }
  SUBCASE("an unknown preset name (it names the run's output files)") {
    SphScene s = c.scene;
    s.preset = "../../etc/x";
    write_sph_checkpoint(path, s, c.state);
    const std::string e = test::checkpoint_read_error(path);
    CHECK(has(e, "SCEN.preset: '../../etc/x' where one of custom, explosion, water"));
  }
}

TEST_CASE("sph checkpoint fields: valid states of every scheme pass, mid-run and after checks") {
  struct Scheme {
    const char* name;
    SphScene scene;
  };
  std::vector<Scheme> schemes;
  for (const SphIntegrator i : {SphIntegrator::euler, SphIntegrator::symplectic_euler,
                                SphIntegrator::rk4, SphIntegrator::leapfrog}) {
    SphScene s = water();
    s.integrator = i;
    schemes.push_back({to_string(i), s});
  }
  schemes.push_back({"dfsph", dfsph_scene()});
  SphScene thesis = make_preset("explosion", 300);
  thesis.model = SphPressureModel::thesis;
  schemes.push_back({"thesis explosion", thesis});
  SphScene obstacle = make_preset("obstacle", 300);
  obstacle.obstacle.pinned = false;
  schemes.push_back({"moving obstacle", obstacle});
  // A fixed dt over the CFL limit: split into sub-steps (substeps > steps).
  SphScene fixed = water();
  fixed.dt = 4e-3;
  schemes.push_back({"fixed dt split", fixed});
  {
    cpu::CpuBackend cpu(1);
    SphSimulation split(cpu, fixed);
    split.run(3);
    REQUIRE(split.substeps() > split.steps());  // the case is what it says
  }
  SphScene fixed_small = water();
  fixed_small.dt = 5e-10;  // below dt_min: taken as it is
  schemes.push_back({"fixed dt below dt_min", fixed_small});
  for (const Scheme& sc : schemes) {
    CAPTURE(sc.name);
    cpu::CpuBackend cpu(1);
    SphSimulation sim(cpu, sc.scene);
    CHECK_NOTHROW(validate_resume_state(sc.scene, sim.export_resume_state()));
    // Past an energy check (every 128 steps), in run()'s blocks, in odd pieces and step by step.
    for (const uint64_t k : {1, 7, 64, 70}) {
      sim.run(k);
      CHECK_NOTHROW(validate_resume_state(sc.scene, sim.export_resume_state()));
    }
    sim.step();
    const SphResumeState r = sim.export_resume_state();
    CHECK_NOTHROW(validate_resume_state(sc.scene, r));
    CHECK(r.good_steps >= SphWatchdog::kEnergyEvery);  // an energy check passed on the way
  }
}
