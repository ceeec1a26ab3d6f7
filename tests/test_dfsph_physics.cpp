// The dfsph pressure model through the simulation driver, on every backend: incompressibility
// (mean compression at most 0.1%) at time steps several times WCSPH's, the solves converging,
// and no preset gaining energy. Test names carry [sph-physics] (see test_sph_physics.cpp).
#include <doctest/doctest.h>

#include <algorithm>
#include <string>

#include "engine/core/error.h"
#include "engine/sph/sph_dfsph_scheme.h"
#include "engine/sph/sph_diagnostics.h"
#include "engine/sph/sph_presets.h"
#include "engine/sph/sph_simulation.h"
#include "tests/backend_fixture.h"
#include "tests/same_bits.h"

using namespace masav;

namespace {

SphScene dfsph_preset(const char* name, uint32_t particles) {
  SphScene s = make_preset(name, particles);
  s.model = SphPressureModel::dfsph;
  s.integrator = SphIntegrator::symplectic_euler;
  return s;
}

}  // namespace

TEST_CASE("[sph-physics] dfsph holds the dam break incompressible at 4x WCSPH's time step") {
  // 4,096 particles through the collapse and the surge along the floor (t = 0.2 s, T = 2.3):
  // the mean compression of the fluid, sampled every step, stays at most 0.1% (the solve stops
  // at a mean residual of 0.01%; measured 0.03%), the largest below 3% (measured 0.9%), and the
  // adaptive step is at least 4x the one WCSPH's speed of sound allows (measured 5.6x at the
  // fastest, where the ratio 0.5 (c0 + v) / v is smallest).
  Backend& b = test::backend();
  SphSimulation sim(b, dfsph_preset("dam-break", 4096));
  const SphScene wc = make_preset("dam-break", 4096);
  double worst_mean = 0, worst_max = 0, smallest_ratio = 1e300;
  while (sim.time() < 0.2) {
    sim.step();
    const SphDiagnostics d = compute_diagnostics(sim.download(), sim);
    REQUIRE(d.finite);
    worst_mean = std::max(worst_mean, d.mean_compression);
    worst_max = std::max(worst_max, d.max_compression);
    // WCSPH's Courant limit at this state: C h / (c0 + v_max).
    const double wcsph_dt =
        wc.cfl_velocity * sim.layout().h / (wc.sound_speed + sim.last_stats().max_speed);
    smallest_ratio = std::min(smallest_ratio, sim.last_dt() / wcsph_dt);
  }
  const SphSolveStats& ss = sim.solve_stats();
  MESSAGE("dfsph dam break to t = " << sim.time() << " s in " << sim.steps() << " steps: mean "
                                    << "compression <= " << worst_mean << ", max " << worst_max
                                    << ", dt >= " << smallest_ratio << " x wcsph's, "
                                    << double(ss.density_iterations) / double(ss.steps)
                                    << " density + "
                                    << double(ss.divergence_iterations) / double(ss.steps)
                                    << " divergence iterations per step");
  CHECK(worst_mean <= 1e-3);
  CHECK(worst_max <= 0.03);
  CHECK(smallest_ratio >= 4.0);
  CHECK(ss.steps == sim.steps());
  CHECK(ss.unconverged == 0);
  CHECK(ss.last_density_error <= sim.scene().dfsph_density_error);
  CHECK(ss.last_divergence_error <= sim.scene().dfsph_divergence_error);
  CHECK(sim.retries() == 0);
}

TEST_CASE("[sph-physics] every preset with dfsph never gains energy") {
  // As the wcsph test (test_sph_physics.cpp), over 300 dfsph steps (about 5x longer each),
  // sampled every 30: kinetic + potential energy (an incompressible fluid stores none) never
  // exceeds its start by more than 0.5%. The explosion starts compressed, which dfsph refuses.
  Backend& b = test::backend();
  for (const auto& info : sph_presets()) {
    CAPTURE(info.name);
    if (info.name == "explosion") {  // starts compressed: refused, naming the field
      CHECK_THROWS_WITH_AS(SphSimulation(b, dfsph_preset("explosion", 512)),
                           doctest::Contains("density_ratio"), Error);
      continue;
    }
    SphSimulation sim(b, dfsph_preset(info.name.c_str(), 512));
    const double e0 = compute_diagnostics(sim.download(), sim).total();
    double worst = -1e300;
    for (int k = 0; k < 10; ++k) {
      sim.run(30);
      const SphDiagnostics d = compute_diagnostics(sim.download(), sim);
      REQUIRE(d.finite);
      CHECK(d.internal == 0);
      worst = std::max(worst, (d.total() - e0) / std::abs(e0));
    }
    MESSAGE(info.name << " (dfsph): largest energy growth " << worst << " of |E0| over "
                      << sim.steps() << " steps to t = " << sim.time() << " s");
    CHECK(worst <= 0.005);
  }
}

TEST_CASE("dfsph queues iterations between residual reads, with the bits of one read each") {
  // The dam break's first steps, once with several iterations per residual read (the default)
  // and once with one: the same positions, velocities and iteration counts, in fewer reads.
  Backend& b = test::backend();
  SphScene scene = dfsph_preset("dam-break", 1024);
  SphSimulation queued(b, scene), one(b, scene);
  one.set_dfsph_queued_iterations(false);
  for (int s = 0; s < 12; ++s) {
    queued.step();
    one.step();
  }
  const SphState a = queued.download(), c = one.download();
  CHECK(test::same_bits(a.positions, c.positions));
  CHECK(test::same_bits(a.velocities, c.velocities));
  CHECK(queued.solve_stats().density_iterations == one.solve_stats().density_iterations);
  CHECK(queued.solve_stats().divergence_iterations == one.solve_stats().divergence_iterations);
  MESSAGE("residual reads in 12 steps: " << queued.dfsph_residual_reads() << " queued, "
                                         << one.dfsph_residual_reads() << " one per iteration");
  CHECK(queued.dfsph_residual_reads() < one.dfsph_residual_reads());
}

TEST_CASE("dfsph_stop_units is the mean residual test as one integer comparison") {
  for (const uint32_t movers : {1u, 3u, 1000u, 1048576u})
    for (const double target : {1e-4, 1e-3, 3e-3, 0.1, 1.0}) {
      CAPTURE(movers);
      CAPTURE(target);
      const uint64_t u = dfsph_stop_units(target, movers);
      auto mean = [&](uint64_t x) { return double(x) / double(kDfsphResidualScale) / movers; };
      CHECK(mean(u) <= target);
      CHECK(mean(u + 1) > target);
    }
}
