// SPH scenes: presets build what the thesis figures describe, particle layouts hold exactly the
// requested count at rest density, and bad input is an error naming the field.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>

#include "engine/core/error.h"
#include "engine/sph/sph_diagnostics.h"
#include "engine/sph/sph_particles.h"
#include "engine/sph/sph_presets.h"
#include "engine/sph/sph_simulation.h"
#include "tests/backend_fixture.h"

using namespace masav;

TEST_CASE("sph presets: exact particle counts, rest density, the thesis's constants") {
  for (const auto& info : sph_presets()) {
    CAPTURE(info.name);
    for (uint32_t n : {1000u, 32768u, 33001u}) {
      CAPTURE(n);
      const SphScene s = make_preset(info.name, n);
      const SphParticles p = build_particles(s);
      CHECK(p.fluid == n);
      CHECK(p.positions.size() == p.total());
      CHECK(p.h == doctest::Approx(2.0 * p.dx));
      CHECK(p.mass > 0);
      CHECK((s.obstacle.enabled ? p.obstacle > 0 : p.obstacle == 0));
    }
  }
  // Figures 4.10-4.13: nu scales with one factor, kp with another; their ratios stay the
  // thesis's.
  const SphScene water = make_preset("water"), mud = make_preset("mud"),
                 boom = make_preset("explosion");
  CHECK(mud.viscosity / water.viscosity == doctest::Approx(3.73e-4 / 5.35e-5));
  CHECK(boom.kp / water.kp == doctest::Approx(1.22e-7 / 1.41e-5));
  CHECK(water.viscosity == doctest::Approx(5.35e-5 * kThesisViscosityScale));
  CHECK(boom.block.density_ratio > 1.0);
  CHECK_THROWS_WITH_AS(make_preset("lava"), doctest::Contains("preset"), Error);
}

TEST_CASE("sph: a block at rest starts at rest density in its interior") {
  SphScene s = make_preset("water", 8000);
  s.gravity = {0, 0, 0};
  SphSimulation sim(test::backend(), s);
  const SphState st = sim.download();
  double interior = 0;
  for (size_t i = 0; i < st.density.size(); ++i) interior = std::max(interior, st.density[i]);
  CHECK(interior == doctest::Approx(1000.0).epsilon(1e-4));  // lattice-normalised mass
  CHECK(sim.last_stats().max_neighbors >= 30);
}

TEST_CASE("sph: bad input names the field, the value and the allowed range") {
  Backend& b = test::backend();
  auto fails = [&](SphScene s, const char* text) {
    CAPTURE(text);
    CHECK_THROWS_WITH_AS(SphSimulation(b, s), doctest::Contains(text), Error);
  };
  const SphScene ok = make_preset("water", 1000);
  SphScene s = ok;
  s.dt = 0.0;
  fails(s, "invalid dt = 0");
  s.dt = -1e-3;
  fails(s, "invalid dt = -0.001");
  s = ok;
  s.particles = 0;
  fails(s, "invalid particles = 0");
  s = ok;
  s.particles = 4'000'000'000u;  // over every device's buffers or memory
  fails(s, "invalid particles = 4000000000");
  s = ok;
  s.smoothing_radius = 0.0;
  fails(s, "invalid smoothing_radius = 0");
  s.smoothing_radius = -0.02;
  fails(s, "smoothing_radius");
  s = ok;
  s.box_max = {0.5, 0.5, 0.5};  // the block reaches 0.7 m
  fails(s, "invalid box");
  s = ok;
  s.viscosity = std::numeric_limits<double>::quiet_NaN();
  fails(s, "invalid viscosity = nan");
  s = ok;
  s.gravity.y = std::numeric_limits<double>::infinity();
  fails(s, "gravity");
  s = ok;
  s.sound_speed = 0;
  fails(s, "sound_speed");
  s = ok;
  s.restitution = 1.5;
  fails(s, "restitution");
  s = ok;
  s.block.min.x = std::nan("");
  fails(s, "block.min");
  CHECK_THROWS_WITH_AS(parse_integrator("rk5"), doctest::Contains("rk4 or leapfrog"), Error);
  CHECK_THROWS_WITH_AS(parse_pressure_model("ideal"), doctest::Contains("wcsph, thesis or dfsph"), Error);
}
