// The SPH stress suite (ctest label `stress`, `ctest --preset stress`; not in the fast run):
// long runs of small scenes for every preset and pressure model, extreme but legal parameters,
// and the guards against NaN and instability. MASAV_STRESS_STEPS overrides the long runs'
// length (default 100,000 steps).
#include <doctest/doctest.h>
#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <string>

#include "engine/core/error.h"
#include "engine/sph/sph_diagnostics.h"
#include "engine/sph/sph_presets.h"
#include "engine/sph/sph_simulation.h"
#include "tests/backend_fixture.h"

using namespace masav;

namespace {

uint64_t stress_steps() {
  if (const char* e = std::getenv("MASAV_STRESS_STEPS")) return std::strtoull(e, nullptr, 10);
  return 100000;
}

// Energy may not grow beyond E0 + energy_growth |E0| at any sample. Walls (mirror images) and
// viscosity only remove energy, so wcsph and dfsph presets are held to 0.5%. Elsewhere the scheme
// is not exactly conservative -- the spiky gradient is not the gradient of the poly6 density, a few
// % of the energy the pressure exchanges, which viscosity usually outweighs -- and the thesis force
// is not symmetric: those runs get the 25% this suite allowed before.
struct Bounds {
  double energy_growth = 0.25;
};
constexpr Bounds kConserving{0.005};

// Runs `steps` steps in 20 chunks; after each: every position and velocity finite, no particle
// outside the box, and energy within the bound.
void long_run(SphScene s, uint64_t steps, const Bounds& b = {}) {
  const auto t0 = std::chrono::steady_clock::now();
  SphSimulation sim(test::backend(), s);
  const SphDiagnostics d0 = compute_diagnostics(sim.download(), sim);
  const double e0 = d0.total();
  double worst = -1e300;
  for (int chunk = 0; chunk < 20; ++chunk) {
    sim.run(steps / 20);
    const SphDiagnostics d = compute_diagnostics(sim.download(), sim);
    REQUIRE(d.finite);
    REQUIRE(d.outside == 0);
    REQUIRE(sim.last_stats().outside == 0);
    worst = std::max(worst, (d.total() - e0) / std::abs(e0));
    CHECK(d.total() <= e0 + b.energy_growth * std::abs(e0));
  }
  const double sec = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  MESSAGE(
      fmt::format("{} / {} / {}: {} steps to t = {:.3f} s in {:.0f} s ({} retried); energy "
                  "{:.4g} J, largest growth {:+.2e} of it",
                  s.preset, to_string(s.model), to_string(s.integrator), sim.steps(), sim.time(),
                  sec, sim.retries(), e0, worst));
}

}  // namespace

TEST_CASE(
    "[stress] every preset and pressure model: 1e5 steps finite, in the box, energy bounded") {
  for (const auto& info : sph_presets()) {
    for (SphPressureModel model :
         {SphPressureModel::wcsph, SphPressureModel::thesis, SphPressureModel::dfsph}) {
      // dfsph is incompressible: the explosion's compressed start is refused (tested in
      // test_dfsph_physics.cpp).
      if (model == SphPressureModel::dfsph && info.name == "explosion") continue;
      const std::string name = info.name + "/" + to_string(model);
      CAPTURE(name);
      SphScene s = make_preset(info.name, 512);
      s.model = model;
      if (model == SphPressureModel::dfsph) s.integrator = SphIntegrator::symplectic_euler;
      if (model == SphPressureModel::thesis && info.name == "dam-break") {
        // The thesis force is not symmetric, so it does not conserve energy: on the dam break's
        // free-slip, nearly inviscid walls its kinetic energy grows without bound (measured: 38 J
        // to 97 J over 25 s, ~100 |E0| by 1e5 steps). With the thesis's own water viscosity and
        // wall constants (as its cube-drop presets use) it still drifts up, slowly (total energy
        // -317 J at 1e4 steps to -184 J at 1e5, E0 = -36 J): bounded over this run, not conserved.
        s.viscosity = kThesisWater.nu * kThesisViscosityScale;
        s.restitution = 0.3;
        s.tangential_damping = 0.01;
      }
      long_run(s, stress_steps(), model == SphPressureModel::thesis ? Bounds{} : kConserving);
    }
  }
}

TEST_CASE("[stress] every integrator on the water drop, 1e4 steps") {
  for (SphIntegrator integ : {SphIntegrator::euler, SphIntegrator::symplectic_euler,
                              SphIntegrator::rk4, SphIntegrator::leapfrog}) {
    const std::string name = to_string(integ);
    CAPTURE(name);
    SphScene s = make_preset("water", 512);
    s.integrator = integ;
    long_run(s, stress_steps() / 10);
  }
}

TEST_CASE("[stress] extreme but legal parameters") {
  const uint64_t n = stress_steps() / 20;
  SUBCASE("zero viscosity, explosion and water") {
    for (const char* p : {"explosion", "water"}) {
      SphScene s = make_preset(p, 512);
      s.viscosity = 0.0;
      long_run(s, n);
    }
  }
  SUBCASE("tiny fixed dt (1 microsecond)") {
    SphScene s = make_preset("dam-break", 512);
    s.dt = 1e-6;
    long_run(s, n);
  }
  SUBCASE("huge fixed dt (50 ms): the guard splits every step") {
    SphScene s = make_preset("water", 512);
    s.dt = 0.05;
    SphSimulation sim(test::backend(), s);
    sim.run(20);
    CHECK(sim.substeps() > 20 * 50);
    const SphDiagnostics d = compute_diagnostics(sim.download(), sim);
    CHECK(d.finite);
    CHECK(d.outside == 0);
  }
  SUBCASE("stiff fluid: c0 = 500 m/s (Tait B = 3.6e10 Pa)") {
    SphScene s = make_preset("dam-break", 512);
    s.sound_speed = 500.0;
    long_run(s, n, kConserving);
  }
  SUBCASE("stiff thesis pressure: kp x 30 runs, kp x 1000 is stopped by the watchdog") {
    SphScene s = make_preset("water", 512);
    s.model = SphPressureModel::thesis;
    // Its gas's speed of sound ~25 m/s, below the scene's c0 = 40.8 m/s (measured: up to
    // 28 m/s; kp x 100, ~46 m/s, reached 60 m/s on lavapipe).
    s.kp *= 30.0;
    long_run(s, n, Bounds{0.2});
    // ~145 m/s: the drop is flung at ~150 m/s, past the watchdog's 2 c0 = 81.7 m/s (the scene
    // claims water with c0 = 40.8 m/s; a gas that fast is not it).
    s.kp *= 1000.0 / 30.0;
    SphSimulation sim(test::backend(), s);
    CHECK_THROWS_WITH_AS(sim.run(n), doctest::Contains("speed bound 81.7 m/s"), Error);
  }
  SUBCASE("fully elastic walls and full tangential damping") {
    SphScene s = make_preset("obstacle", 512);
    s.restitution = 1.0;
    s.tangential_damping = 1.0;
    long_run(s, n);
  }
  SUBCASE("heavy obstacle that moves (mass ratio 1e3)") {
    SphScene s = make_preset("obstacle", 512);
    s.obstacle.pinned = false;
    s.obstacle.mass_ratio = 1e3;
    long_run(s, n);
  }
}

TEST_CASE("[stress] NaN and instability are caught within one step, for every integrator") {
  for (SphIntegrator integ : {SphIntegrator::euler, SphIntegrator::symplectic_euler,
                              SphIntegrator::rk4, SphIntegrator::leapfrog}) {
    const std::string name = to_string(integ);
    CAPTURE(name);
    SphScene s = make_preset("dam-break", 512);
    s.integrator = integ;
    SphSimulation sim(test::backend(), s);
    sim.run(500);
    SphState st = sim.download();
    st.velocities[77].z = std::numeric_limits<double>::infinity();
    sim.set_velocities(st.velocities);
    CHECK_THROWS_WITH_AS(sim.step(), doctest::Contains("step 501"), Error);
    CHECK_THROWS_WITH_AS(sim.step(), doctest::Contains("particle 77"), Error);
    CHECK(sim.steps() == 500);
  }
  // A fixed dt 20x the CFL limit with the guard set to stop: an error with advice, not a blow-up.
  SphScene s = make_preset("dam-break", 512);
  s.cfl_guard = SphCflGuard::stop;
  SphSimulation probe(test::backend(), s);
  s.dt = 20 * probe.dt_limit();
  SphSimulation sim(test::backend(), s);
  CHECK_THROWS_WITH_AS(sim.step(), doctest::Contains("exceeds the CFL limit"), Error);
}
