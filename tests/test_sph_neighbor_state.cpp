// The neighbour state (sph_density's optional output neighbor_state, sph_forces' optional input;
// kSphStateStride in engine/kernels/sph_kernel_params.h), one test body on every backend. The
// records hold the particle's own position and velocity, the density sph_density wrote and
// p / rho^2 of the pressure it wrote; sph_forces over them must give the bits it gives over the
// four arrays, with and without the row masks: the same values reach the same pair terms in the
// same order, and p / rho^2 is one shared expression in both kernels.
#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <utility>
#include <vector>

#include "engine/core/error.h"
#include "engine/kernels/sph_kernels.h"
#include "engine/sph/sph_kernel_calls.h"
#include "tests/backend_fixture.h"
#include "tests/sph_fixture.h"
#include "tests/sph_state_compare.h"
#include "tests/sph_switch_run.h"

using namespace masav;

namespace {

bool same_bits(const std::vector<Vec4d>& a, const std::vector<Vec4d>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(Vec4d)) == 0;
}

// Whether the backend computes in double (the CPU reference): its p / rho^2 is then the host's.
bool in_double(const Backend& b) {
  return b.caps().backend == "cpu";
}

void check_state_and_forces(Backend& b, const test::SphCase& c) {
  const uint32_t n = c.params.n;
  test::SphBuffers s = test::upload_sph_case(b, c);
  auto state = b.create<Real4>(size_t(kSphStateStride) * n, "test neighbour state");
  auto forces = [&](const Buffer<Real4>* with_state, const Buffer<uint32_t>* rows,
                    const Buffer<Real4>* velocities = nullptr) {
    SphForcesIO io{&s.sorted_pos, velocities ? velocities : &s.sorted_vel,
                   &s.density,    &s.pressure,
                   s.view(),      &s.accel,
                   &s.stats,      rows};
    io.neighbor_state = with_state;
    sph_forces(b, c.params, io);
    return b.download(s.accel);
  };
  // Without the state first: the density and pressure it must leave as they are.
  sph_density(b, c.params, {&s.sorted_pos, s.view(), &s.density, &s.pressure, &s.stats});
  const auto plain_rho = b.download(s.density), plain_p = b.download(s.pressure);
  SphDensityIO io{&s.sorted_pos, s.view(), &s.density, &s.pressure, &s.stats, &s.neighbor_rows};
  io.velocities = &s.sorted_vel;
  io.neighbor_state = &state;
  sph_density(b, c.params, io);
  const auto rho = b.download(s.density), pr = b.download(s.pressure);
  CHECK(rho == plain_rho);
  CHECK(pr == plain_p);
  const auto x = b.download(s.sorted_pos), v = b.download(s.sorted_vel);
  const auto got = b.download(state);
  for (uint32_t i = 0; i < n; ++i) {
    CAPTURE(i);
    const Vec4d a = got[kSphStateStride * i], q = got[kSphStateStride * i + 1];
    REQUIRE((a.x == x[i].x && a.y == x[i].y && a.z == x[i].z && a.w == rho[i]));
    REQUIRE((q.x == v[i].x && q.y == v[i].y && q.z == v[i].z));
    if (in_double(b)) {
      REQUIRE(q.w == sph::pressure_over_rho2(pr[i], rho[i]));
    } else {
      const double want = double(sph::pressure_over_rho2(float(pr[i]), float(rho[i])));
      REQUIRE(std::abs(q.w - want) <= 1e-6 * std::abs(want));  // GPU divisions: 2-3 ulp
    }
  }
  // Over the state, the forces' bits are those over the four arrays, walked whole or by masks.
  CHECK(same_bits(forces(&state, nullptr), forces(nullptr, nullptr)));
  CHECK(same_bits(forces(&state, &s.neighbor_rows), forces(nullptr, &s.neighbor_rows)));
  // And they are read from the state: one made with the particles at rest gives the forces of
  // the particles at rest (the viscosity term differs), whatever the velocities array holds.
  auto at_rest = b.create<Real4>(n, "test velocities at rest");
  b.upload(at_rest, std::vector<Vec4d>(n, Vec4d{}));
  io.velocities = &at_rest;
  sph_density(b, c.params, io);
  const auto over_rest_state = forces(&state, &s.neighbor_rows);
  CHECK(same_bits(over_rest_state, forces(nullptr, &s.neighbor_rows, &at_rest)));
  CHECK_FALSE(same_bits(over_rest_state, forces(nullptr, &s.neighbor_rows)));
}

}  // namespace

TEST_CASE("sph_density's neighbour state; sph_forces over it gives the same bits") {
  Backend& b = test::backend();
  test::for_each_model_and_walls(12, 47, [&](test::SphCase& c) { check_state_and_forces(b, c); });
  SUBCASE("dfsph (viscosity only)") {
    test::SphCase c = test::make_sph_case(10, SphPressureModel::dfsph, 48);
    check_state_and_forces(b, c);
  }
}

TEST_CASE("sph kernels reject a neighbour state that is too small, aliased or without velocities") {
  Backend& b = test::backend();
  const test::SphCase c = test::make_sph_case(4, SphPressureModel::wcsph, 1);
  test::SphBuffers s = test::upload_sph_case(b, c);
  auto small = b.create<Real4>(size_t(kSphStateStride) * c.params.n - 1, "short state");
  auto state = b.create<Real4>(size_t(kSphStateStride) * c.params.n, "state");
  auto density = [&](Buffer<Real4>* st, const Buffer<Real4>* vel) {
    SphDensityIO io{&s.sorted_pos, s.view(), &s.density, &s.pressure, &s.stats};
    io.velocities = vel;
    io.neighbor_state = st;
    sph_density(b, c.params, io);
  };
  CHECK_THROWS_WITH_AS(density(&small, &s.sorted_vel), doctest::Contains("neighbor_state size"),
                       Error);
  CHECK_THROWS_WITH_AS(density(&state, nullptr), doctest::Contains("'velocities'"), Error);
  CHECK_THROWS_WITH_AS(density(&s.sorted_vel, &s.sorted_vel), doctest::Contains("neighbor_state"),
                       Error);
  SphForcesIO io{&s.sorted_pos, &s.sorted_vel, &s.density, &s.pressure,
                 s.view(),      &s.accel,      &s.stats};
  io.neighbor_state = &small;
  CHECK_THROWS_WITH_AS(sph_forces(b, c.params, io), doctest::Contains("neighbor_state size"),
                       Error);
  io.neighbor_state = &s.accel;
  CHECK_THROWS_WITH_AS(sph_forces(b, c.params, io), doctest::Contains("neighbor_state"), Error);
}

namespace {

// A dam break with `integrator` on a backend whose sph.neighbor_state is `state`; whether the
// simulation kept the state.
SphState run_dam_break(Backend& b, SphIntegrator integrator, bool& kept) {
  test::SwitchRun r = test::run_dam_break_on(b, integrator);
  kept = r.neighbor_state;
  return std::move(r.state);
}

}  // namespace

TEST_CASE("[sph-physics] a dam break over the neighbour state keeps the trajectory bit for bit") {
  Tuning t = test::tuning();
  t.sph.neighbor_state = Choice::on;
  const std::unique_ptr<Backend> with_state = test::backend_with(t);
  t.sph.neighbor_state = Choice::off;
  const std::unique_ptr<Backend> without_state = test::backend_with(t);
  for (const SphIntegrator integrator :
       {SphIntegrator::euler, SphIntegrator::leapfrog, SphIntegrator::rk4}) {
    CAPTURE(to_string(integrator));
    bool with = false, without = true;
    const SphState on = run_dam_break(*with_state, integrator, with);
    const SphState off = run_dam_break(*without_state, integrator, without);
    CHECK(with);
    CHECK_FALSE(without);
    CHECK(test::same_state(on, off));
  }
}
