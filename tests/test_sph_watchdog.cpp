// The stability watchdog (engine/sph/sph_watchdog.h) on every backend: the blow-ups that used to
// pass silently stop with the step, the quantity, the value and the bound, and keep the last
// good state; the density statistic it reads matches the densities; a sane run never trips it.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "engine/core/error.h"
#include "engine/sph/sph_diagnostics.h"
#include "engine/sph/sph_presets.h"
#include "engine/sph/sph_simulation.h"
#include "tests/backend_fixture.h"

using namespace masav;

namespace {

// Runs `steps` steps; the watchdog's message, or empty.
std::string run_until_stopped(SphSimulation& sim, uint64_t steps) {
  try {
    sim.run(steps);
  } catch (const Error& e) {
    return e.what();
  }
  return {};
}

}  // namespace

TEST_CASE("[sph-physics] the watchdog stops a run whose speeds blow up, at the step") {
  // The thesis gas at kp = 1e9 and 10 us steps with the guard off: its first step flings
  // particles to ~7e5 m/s. (Slower blow-ups move a particle past h first: the next case.)
  SphScene s = make_preset("water", 1000);
  s.model = SphPressureModel::thesis;
  s.kp = 1e9;
  s.dt = 1e-5;
  s.cfl_guard = SphCflGuard::off;
  SphSimulation sim(test::backend(), s);
  const std::string msg = run_until_stopped(sim, 200);
  INFO(msg);
  CHECK(msg.find("sph watchdog: step ") != std::string::npos);
  CHECK(msg.find("above the watchdog's speed bound 81.7 m/s") != std::string::npos);
  CHECK(msg.find("smaller dt") != std::string::npos);
  CHECK(sim.steps() < 30);
  // The state kept is the last good one: finite, in the box, below the bound.
  const SphDiagnostics d = compute_diagnostics(sim.download(), sim);
  CHECK(d.finite);
  CHECK(d.max_speed <= 81.7);  // 2 c0
  CHECK(msg.find("step " + std::to_string(sim.steps() + 1) + " ") != std::string::npos);
}

TEST_CASE("[sph-physics] the watchdog stops a run whose energy doubles, back at the last check") {
  // Explicit Euler gains energy every step on an oscillation, and with elastic walls, no
  // viscosity and a fixed dt at 0.82 of the initial CFL limit (the guard off) nothing takes it
  // away: the dam break's energy doubles within ~500 steps of 1,000 particles, before any speed or
  // density bound is reached.
  SphScene s = make_preset("dam-break", 1000);
  s.integrator = SphIntegrator::euler;
  s.dt = 4e-4;
  s.cfl_guard = SphCflGuard::off;
  s.restitution = 1.0;
  s.viscosity = 0.0;
  SphSimulation sim(test::backend(), s);
  const double e0 = available_energy(sim.download(), sim);
  const std::string msg = run_until_stopped(sim, 4000);
  INFO(msg);
  CHECK(msg.find("the energy above the floor reached") != std::string::npos);
  CHECK(msg.find("the last that passed") != std::string::npos);
  REQUIRE(sim.steps() > 0);
  CHECK(sim.steps() % SphWatchdog::kEnergyEvery == 0);
  const double e = available_energy(sim.download(), sim);
  CHECK(e <= e0 * (1 + SphWatchdog::kEnergyMargin));
  CHECK(e > e0);  // it was on its way up
  // The run can go on from there (and stops again further on).
  CHECK_FALSE(run_until_stopped(sim, 4000).empty());
}

TEST_CASE("[sph-physics] the watchdog stops a step past h under every pressure model") {
  // 0.1 s steps with the guard off: the water falls 0.1 m in its first steps, past h = 0.1 m
  // neighbours it never saw. The thesis gas's energy check cannot see it (its isothermal
  // expansion energy has no floor: the run kept "conserving" energy at 20-40 m/s in a 1 m box),
  // so the step's own reach is the bound, for every model and integrator.
  for (const char* model : {"wcsph", "thesis", "dfsph"})
    for (SphIntegrator integ : {SphIntegrator::euler, SphIntegrator::symplectic_euler,
                                SphIntegrator::leapfrog, SphIntegrator::rk4}) {
      SphScene s = make_preset("water", 500);
      s.model = parse_pressure_model(model);
      if (s.model == SphPressureModel::dfsph && integ != SphIntegrator::symplectic_euler) continue;
      s.integrator = integ;
      s.dt = 0.1;
      s.cfl_guard = SphCflGuard::off;
      const std::string name = std::string(model) + " " + to_string(integ);
      CAPTURE(name);
      SphSimulation sim(test::backend(), s);
      const std::string msg = run_until_stopped(sim, 400);
      // RK4's own check of its stages' reach (the grid's skin) stops it first.
      const bool rk4 = integ == SphIntegrator::rk4;
      CHECK(msg.find(rk4 ? "sph cfl guard: step " : "sph watchdog: step ") != std::string::npos);
      CHECK(msg.find(rk4 ? "an RK4 stage moved a particle" : "more than the support radius h") !=
            std::string::npos);
      CHECK(sim.steps() < 5);
      CHECK(compute_diagnostics(sim.download(), sim).finite);
    }
}

TEST_CASE("[sph-physics] the watchdog leaves a sane run alone; its density statistic is exact") {
  // (The fluid's largest density is a fluid particle's here: the dam break has no obstacle.)
  SphScene s = make_preset("dam-break", 1000);
  s.integrator = SphIntegrator::leapfrog;  // the last force pass ran at the committed state
  SphSimulation sim(test::backend(), s);
  sim.set_block_steps(1);
  CHECK(run_until_stopped(sim, 300).empty());
  const SphState st = sim.download();
  const double rho = *std::max_element(st.density.begin(), st.density.end());
  CHECK(sim.last_stats().max_density == doctest::Approx(rho).epsilon(1e-6));
  CHECK(rho > s.rest_density);
  // The compression the CSV and `bench sph` report: max(rho / rho0 - 1, 0) of the fluid.
  const SphDiagnostics d = compute_diagnostics(st, sim);
  CHECK(d.max_compression == doctest::Approx(rho / s.rest_density - 1));
  CHECK(d.mean_compression > 0);
  CHECK(d.mean_compression < d.max_compression);
  // The 99.9th percentile: at least 99.9% of the fluid at or below it, fewer below any less.
  std::vector<double> c;
  for (size_t i = 0; i < sim.layout().fluid; ++i)
    c.push_back(std::max(st.density[i] / s.rest_density - 1.0, 0.0));
  const auto at_most = [&](double v) {
    return double(std::count_if(c.begin(), c.end(), [&](double x) { return x <= v; }));
  };
  CHECK(at_most(d.p999_compression) >= 0.999 * double(c.size()));
  CHECK(at_most(std::nextafter(d.p999_compression, 0.0)) < 0.999 * double(c.size()));
  CHECK(d.p999_compression <= d.max_compression);
  const auto columns = diagnostics_columns();
  CHECK(columns.size() == diagnostics_row(sim, d).size());
  CHECK(columns.back() == "p999_compression");
}
