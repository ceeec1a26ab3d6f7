// drift_points: equals the CPU reference within its stated tolerance (engine/points/
// drift_compare.h), keeps every point in the box, starts at the uniforms, and moves each point
// at the speed it reports.
#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include "engine/core/error.h"
#include "engine/points/drift_compare.h"
#include "tests/backend_fixture.h"

using namespace masav;

namespace {

struct Cloud {
  Buffer<float> start, direction;
  Buffer<Real4> positions;
};

Cloud make_cloud(Backend& b, uint32_t n, uint64_t seed) {
  Cloud c{b.create<float>(4 * size_t(n), "start"), b.create<float>(4 * size_t(n), "direction"),
          b.create<Real4>(n, "positions")};
  b.philox_uniform({seed, 0, 0}, c.start);
  b.philox_uniform({seed, 1, 0}, c.direction);
  return c;
}

std::vector<Vec4d> drift_on(Backend& b, const DriftParams& p, uint64_t seed) {
  Cloud c = make_cloud(b, p.n, seed);
  b.drift_points(p, c.start, c.direction, c.positions);
  return b.download(c.positions);
}

DriftParams params(uint32_t n, float speed, float time_s) {
  DriftParams p;
  p.n = n;
  p.box_lo = {-1.5f, 0.25f, 3.0f};
  p.box_extent = {3.0f, 0.5f, 2.0f};
  p.speed = speed;
  p.time_s = time_s;
  return p;
}

}  // namespace

TEST_CASE("drift_points equals the CPU reference within its stated tolerance") {
  for (const DriftParams& p :
       {params(0, 0.1f, 1.0f), params(1, 0.1f, 1.0f), params(100003, 0.07f, 0.0f),
        params(100003, 0.07f, 12.5f), params(4097, 3.0f, 1000.0f)}) {
    CAPTURE(p.n);
    CAPTURE(p.time_s);
    const auto got = drift_on(test::backend(), p, 9);
    const auto want = drift_on(test::reference(), p, 9);
    const DriftError e = compare_drift(p, got, want);
    const DriftTolerance tol = drift_tolerance(p);
    MESSAGE("max position error " << e.max_position_abs << " (tolerance " << tol.position_abs
                                  << "), max speed rel " << e.max_speed_rel);
    CHECK(e.non_finite == 0);
    CHECK(e.max_position_abs <= tol.position_abs);
    CHECK(e.max_speed_rel <= tol.speed_rel);
  }
}

TEST_CASE("drifting points stay in the box, start at the uniforms and move at their speed") {
  Backend& b = test::backend();
  const uint32_t n = 20000;
  DriftParams p = params(n, 0.05f, 0.0f);
  Cloud c = make_cloud(b, n, 4);
  const auto u = b.download(c.start), w = b.download(c.direction);
  b.drift_points(p, c.start, c.direction, c.positions);
  const auto at0 = b.download(c.positions);
  const double lo[3] = {p.box_lo.x, p.box_lo.y, p.box_lo.z};
  const double ext[3] = {p.box_extent.x, p.box_extent.y, p.box_extent.z};
  for (uint32_t i = 0; i < n; i += 7) {
    const double q[3] = {at0[i].x, at0[i].y, at0[i].z};
    for (int a = 0; a < 3; ++a) REQUIRE(std::abs(q[a] - (lo[a] + ext[a] * u[4 * i + a])) <= 1e-6);
  }
  // A small step moves each point by velocity * dt (unless it wrapped around the box).
  const float dt = 0.01f;
  p.time_s = 2.0f;
  b.drift_points(p, c.start, c.direction, c.positions);
  const auto t1 = b.download(c.positions);
  p.time_s = 2.0f + dt;
  b.drift_points(p, c.start, c.direction, c.positions);
  const auto t2 = b.download(c.positions);
  size_t checked = 0;
  for (uint32_t i = 0; i < n; ++i) {
    const double a1[3] = {t1[i].x, t1[i].y, t1[i].z}, a2[3] = {t2[i].x, t2[i].y, t2[i].z};
    double moved2 = 0;
    bool wrapped = false;
    for (int a = 0; a < 3; ++a) {
      REQUIRE(a2[a] >= lo[a]);
      REQUIRE(a2[a] <= lo[a] + ext[a]);
      double d = a2[a] - a1[a];
      if (std::abs(d) > 0.5 * ext[a]) {  // wrapped around the periodic box: unwrap
        wrapped = true;
        d -= std::copysign(ext[a], d);
      }
      const double v = (2.0 * w[4 * i + a] - 1.0) * p.speed * ext[a];
      REQUIRE(std::abs(d - v * dt) <= 1e-5 * (1 + ext[a]));
      moved2 += d * d;
    }
    if (wrapped) continue;  // its reported speed is checked on the unwrapped ones
    ++checked;
    CHECK(std::sqrt(moved2) / dt == doctest::Approx(t2[i].w).epsilon(2e-3));
  }
  CHECK(checked > n * 9 / 10);
}

TEST_CASE("drift_points rejects bad parameters, naming the field") {
  Backend& b = test::backend();
  Cloud c = make_cloud(b, 8, 1);
  DriftParams p = params(9, 0.1f, 0.0f);
  CHECK_THROWS_WITH_AS(b.drift_points(p, c.start, c.direction, c.positions),
                       doctest::Contains("n = 9"), Error);
  p = params(8, -1.0f, 0.0f);
  CHECK_THROWS_WITH_AS(b.drift_points(p, c.start, c.direction, c.positions),
                       doctest::Contains("speed"), Error);
  p = params(8, 0.1f, NAN);
  CHECK_THROWS_WITH_AS(b.drift_points(p, c.start, c.direction, c.positions),
                       doctest::Contains("time_s"), Error);
  p = params(8, 0.1f, 0.0f);
  p.box_extent.y = 0.0f;
  CHECK_THROWS_WITH_AS(b.drift_points(p, c.start, c.direction, c.positions),
                       doctest::Contains("box_extent"), Error);
}
