// The SPH kernels over a range of particles, [first, first + count) of the n (a rank's own
// particles among its halos, engine/sph/sph_ranks.h), on every backend: inside the range the
// same bits as one call over every particle, outside it every output untouched, and the stats of
// the range's particles alone (two ranges that split the particles give the whole call's).
#include <doctest/doctest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <vector>

#include "engine/core/error.h"
#include "engine/sph/dfsph_case_buffers.h"
#include "engine/sph/sph_kernel_calls.h"
#include "engine/sph/sph_particles.h"
#include "tests/backend_fixture.h"
#include "tests/sph_fixture.h"

using namespace masav;

namespace {

constexpr uint32_t kUntouched = 0x7ff8dead;  // a NaN in float and, doubled, in double

struct Range {
  uint32_t first, count;
};

bool same_bits(double a, double b) {
  return std::bit_cast<uint64_t>(a) == std::bit_cast<uint64_t>(b);
}

// `got` equals `want` inside the range, bit for bit (to fp32 rounding where the sums' order
// follows the lanes: the range moves a particle to another lane), and is the untouched NaN
// outside it.
template <class Get>
void check_range(size_t n, Range r, Get get, const char* what) {
  CAPTURE(what);
  const bool exact = !test::sph_sums_follow_lanes();
  double scale = 0;  // the largest |want|: sums of terms that cancel round to it
  for (size_t i = 0; i < n; ++i) scale = std::max(scale, std::abs(get(i).second));
  size_t wrong_inside = 0, touched_outside = 0;
  for (size_t i = 0; i < n; ++i) {
    const auto [g, w] = get(i);
    const bool inside = i >= r.first && i < size_t(r.first) + r.count;
    const bool equal = exact ? same_bits(g, w) : std::abs(g - w) <= 2e-6 * scale;
    if (inside && !equal) ++wrong_inside;
    if (!inside && !std::isnan(g)) ++touched_outside;
  }
  CHECK(wrong_inside == 0);
  CHECK(touched_outside == 0);
}

// The same for a per-particle array against the whole call's.
template <class T>
void check_range(size_t n, Range r, const std::vector<T>& got, const std::vector<T>& want,
                 const char* what) {
  check_range(
      n, r,
      [&](size_t i) {
        return std::pair{double(got[i]), double(want[i])};
      },
      what);
}

}  // namespace

namespace masav::test {
namespace {

// The residual dfsph_rate summed into slot `slot` (a 64-bit integer in two words).
uint64_t residual_units(const std::vector<uint32_t>& words, uint32_t slot) {
  return uint64_t(words[2 * slot + 1]) << 32 | words[2 * slot];
}

}  // namespace
}  // namespace masav::test

TEST_CASE("sph kernels over a particle range: the whole call's values inside, nothing outside") {
  Backend& b = test::backend();
  test::SphCase c = test::make_sph_case(12, SphPressureModel::wcsph, 21);
  test::with_walls(c, true);
  const uint32_t n = c.params.n;
  test::SphBuffers all = test::upload_sph_case(b, c);
  sph_density(
      b, c.params,
      {&all.sorted_pos, all.view(), &all.density, &all.pressure, &all.stats, &all.neighbor_rows});
  sph_forces(b, c.params,
             {&all.sorted_pos, &all.sorted_vel, &all.density, &all.pressure, all.view(), &all.accel,
              &all.stats, &all.neighbor_rows});
  SphIntegrateParams ip;
  ip.n = n;
  ip.op = SphStageOp::symplectic_euler;
  ip.dt = 1e-3;
  ip.box_min = c.params.box_min;
  ip.box_max = c.params.box_max;
  Buffer<Real4> x_all = b.create<Real4>(n, "x all"), v_all = b.create<Real4>(n, "v all");
  sph_integrate(b, ip,
                {&all.sorted_pos, &all.sorted_vel, nullptr, &all.accel, &x_all, &v_all, nullptr,
                 nullptr, &all.stats});
  const auto rho = b.download(all.density), pr = b.download(all.pressure);
  const auto acc = b.download(all.accel), x1 = b.download(x_all), v1 = b.download(v_all);

  for (const Range r : {Range{0, n}, Range{137, 1234}, Range{n - 1, 1}, Range{500, 0},
                        Range{n / 3, kSphAllParticles}, Range{n / 2 + 5, n / 2 - 5}}) {
    CAPTURE(r.first);
    CAPTURE(r.count);
    const Range span{r.first, r.count == kSphAllParticles ? n - r.first : r.count};
    test::SphBuffers s = test::upload_sph_case(b, c);
    SphStepParams p = c.params;
    p.first = r.first;
    p.count = r.count;
    b.fill(s.density, kUntouched);
    b.fill(s.pressure, kUntouched);
    sph_density(b, p,
                {&s.sorted_pos, s.view(), &s.density, &s.pressure, &s.stats, &s.neighbor_rows});
    const auto d = b.download(s.density), q = b.download(s.pressure);
    check_range(n, span, d, rho, "density");
    check_range(n, span, q, pr, "pressure");

    // Forces read every particle's density and pressure (a halo's come from its owner).
    b.upload(s.density, rho);
    b.upload(s.pressure, pr);
    b.fill(s.accel, kUntouched);
    sph_forces(b, p,
               {&s.sorted_pos, &s.sorted_vel, &s.density, &s.pressure, s.view(), &s.accel, &s.stats,
                &s.neighbor_rows});
    const auto a = b.download(s.accel);
    check_range(
        n, span,
        [&](size_t i) {
          return std::pair{a[i].x, acc[i].x};
        },
        "accel x");
    check_range(
        n, span,
        [&](size_t i) {
          return std::pair{a[i].z, acc[i].z};
        },
        "accel z");
    check_range(
        n, span,
        [&](size_t i) {
          return std::pair{a[i].w, acc[i].w};
        },
        "neighbours");

    SphIntegrateParams ir = ip;
    ir.first = r.first;
    ir.count = r.count;
    b.upload(s.accel, acc);
    b.fill(s.pos, kUntouched);
    b.fill(s.vel, kUntouched);
    sph_integrate(b, ir,
                  {&s.sorted_pos, &s.sorted_vel, nullptr, &s.accel, &s.pos, &s.vel, nullptr,
                   nullptr, &s.stats});
    const auto xo = b.download(s.pos), vo = b.download(s.vel);
    check_range(
        n, span,
        [&](size_t i) {
          return std::pair{xo[i].y, x1[i].y};
        },
        "x_out");
    check_range(
        n, span,
        [&](size_t i) {
          return std::pair{vo[i].x, v1[i].x};
        },
        "v_out");
  }
}

TEST_CASE("sph kernels over two ranges that split the particles report the whole call's stats") {
  Backend& b = test::backend();
  test::SphCase c = test::make_sph_case(11, SphPressureModel::wcsph, 5);
  const uint32_t n = c.params.n;
  test::SphBuffers all = test::upload_sph_case(b, c);
  sph_density(b, c.params, {&all.sorted_pos, all.view(), &all.density, &all.pressure, &all.stats});
  const auto rho = b.download(all.density), pr = b.download(all.pressure);
  // Density, forces and a step over [first, first + count), into one stats buffer.
  auto stats_of = [&](uint32_t first, uint32_t count) {
    test::SphBuffers s = test::upload_sph_case(b, c);
    SphStepParams p = c.params;
    p.first = first;
    p.count = count;
    sph_density(b, p, {&s.sorted_pos, s.view(), &s.density, &s.pressure, &s.stats});
    b.upload(s.density, rho);  // forces read every particle's (a halo's from its owner)
    b.upload(s.pressure, pr);
    sph_forces(
        b, p,
        {&s.sorted_pos, &s.sorted_vel, &s.density, &s.pressure, s.view(), &s.accel, &s.stats});
    SphIntegrateParams ip;
    ip.n = n;
    ip.first = first;
    ip.count = count;
    ip.dt = 2e-3;
    ip.op = SphStageOp::euler;
    // A box through the particles: the ones a step ends outside it are counted.
    ip.walls = false;
    ip.box_min = {0.06, 0.0, 0.0};
    ip.box_max = {0.12, 1.0, 1.0};
    sph_integrate(b, ip,
                  {&s.sorted_pos, &s.sorted_vel, nullptr, &s.accel, &s.pos, &s.vel, nullptr,
                   nullptr, &s.stats});
    return b.download(s.stats);
  };
  const uint32_t k = n / 2 + 77;
  const auto whole = stats_of(0, n), lo = stats_of(0, k), hi = stats_of(k, n - k);
  for (uint32_t w : {kSphStatMaxCandidates, kSphStatMaxSpeed2, kSphStatMaxAccel2, kSphStatMaxDisp2,
                     kSphStatMaxNeighbors, kSphStatMaxDensity}) {
    CAPTURE(w);
    CHECK(std::max(lo[w], hi[w]) == whole[w]);
  }
  // Each part sees less than the whole somewhere (the maxima lie in one of them).
  CHECK(std::min(lo[kSphStatMaxDensity], hi[kSphStatMaxDensity]) < whole[kSphStatMaxDensity]);
  CHECK(std::min(lo[kSphStatMaxAccel2], hi[kSphStatMaxAccel2]) < whole[kSphStatMaxAccel2]);
  CHECK(whole[kSphStatOutside] > 0);
  CHECK(lo[kSphStatOutside] + hi[kSphStatOutside] == whole[kSphStatOutside]);
  // An empty range reports nothing.
  const auto none = stats_of(100, 0);
  CHECK(none[kSphStatMaxDensity] == 0);
  CHECK(none[kSphStatMaxSpeed2] == 0);
}

TEST_CASE("dfsph kernels over a particle range: the whole call's values inside, nothing outside") {
  // A rank's solve (engine/sph/sph_dfsph_scheme.cpp) runs the three kernels over its own
  // particles, the halos' factor, kappa and velocities coming from their owners.
  Backend& b = test::backend();
  test::SphCase c = test::make_sph_case(12, SphPressureModel::dfsph, 8);
  c.params.mass = lattice_mass(1000.0, c.dx, c.params.h, true);
  test::with_walls(c, true);
  const uint32_t n = c.params.n;
  const double dt = 2e-3;
  // The whole call: factor, then one density-solve iteration (rate, correct) from kappa sums of 0.
  test::SphBuffers all = test::upload_sph_case(b, c);
  DfsphCaseBuffers dk = make_dfsph_buffers(b, n, "whole");
  sph_density(b, c.params, {&all.sorted_pos, all.view(), &all.density, &all.pressure, &all.stats});
  const DfsphIO whole = dfsph_io(all, dk);
  dfsph_factor(b, DfsphParams{c.params}, whole);
  const DfsphParams solve{c.params, DfsphSolve::density, dt};
  dfsph_rate(b, solve, whole);
  const auto f_all = b.download(dk.factor), k_all = b.download(dk.kappa),
             sum_all = b.download(dk.kappa_sum);
  const auto v0 = b.download(all.sorted_vel);
  dfsph_correct(b, solve, whole);
  const auto v_all = b.download(all.sorted_vel);
  const uint64_t residual_all = test::residual_units(b.download(dk.residual), 0);
  REQUIRE(residual_all > 0);  // the jittered lattice is compressed somewhere

  uint64_t residual_split = 0;
  for (const Range r : {Range{0, n}, Range{137, 1234}, Range{n - 1, 1}, Range{500, 0},
                        Range{0, n / 2 + 5}, Range{n / 2 + 5, kSphAllParticles}}) {
    CAPTURE(r.first);
    CAPTURE(r.count);
    const Range span{r.first, r.count == kSphAllParticles ? n - r.first : r.count};
    auto inside = [&](size_t i) { return i >= span.first && i < size_t(span.first) + span.count; };
    test::SphBuffers s = test::upload_sph_case(b, c);
    DfsphCaseBuffers k = make_dfsph_buffers(b, n, "range");
    b.upload(s.density, b.download(all.density));
    DfsphParams p{c.params, DfsphSolve::density, dt};
    p.step.first = r.first;
    p.step.count = r.count;
    const DfsphIO io = dfsph_io(s, k);
    b.fill(k.factor, kUntouched);
    dfsph_factor(b, p, io);
    const auto f = b.download(k.factor);
    check_range(n, span, f, f_all, "factor");

    // The rate reads every particle's velocity and its own factor and kappa sum; it writes the
    // range's kappa and kappa sums.
    b.upload(k.factor, f_all);
    std::vector<double> sums(n);
    for (size_t i = 0; i < n; ++i) sums[i] = inside(i) ? 0.0 : std::bit_cast<float>(kUntouched);
    b.upload(k.kappa_sum, sums);
    b.fill(k.kappa, kUntouched);
    dfsph_rate(b, p, io);
    const auto kap = b.download(k.kappa), sum = b.download(k.kappa_sum);
    check_range(n, span, kap, k_all, "kappa");
    check_range(n, span, sum, sum_all, "kappa sum");
    const uint64_t units = test::residual_units(b.download(k.residual), 0);
    if (span.count == n) CHECK(units == residual_all);
    if (r.count == n / 2 + 5 || (r.first == n / 2 + 5)) residual_split += units;

    // The correction reads every particle's kappa (a halo's from its owner); it changes the
    // range's velocities only.
    b.upload(k.kappa, k_all);
    dfsph_correct(b, p, io);
    const auto v = b.download(s.sorted_vel);
    const bool exact = !test::sph_sums_follow_lanes();
    size_t wrong_inside = 0, touched_outside = 0;
    for (size_t i = 0; i < n; ++i) {
      if (!inside(i)) {
        if (!same_bits(v[i].x, v0[i].x) || !same_bits(v[i].z, v0[i].z)) ++touched_outside;
      } else if (exact ? !same_bits(v[i].x, v_all[i].x) || !same_bits(v[i].z, v_all[i].z)
                       : std::abs(v[i].x - v_all[i].x) > 1e-5 ||
                             std::abs(v[i].z - v_all[i].z) > 1e-5) {
        ++wrong_inside;
      }
    }
    CHECK(wrong_inside == 0);
    CHECK(touched_outside == 0);
  }
  // Two ranges that split the particles: their residuals add up to the whole call's (integers;
  // within a unit per particle where the lanes' sums round differently).
  if (test::sph_sums_follow_lanes())
    CHECK(double(residual_split) == doctest::Approx(double(residual_all)).epsilon(1e-3));
  else
    CHECK(residual_split == residual_all);
}

TEST_CASE("sph kernel ranges beyond the particles are rejected, naming the field") {
  Backend& b = test::backend();
  const test::SphCase c = test::make_sph_case(4, SphPressureModel::wcsph, 1);
  test::SphBuffers s = test::upload_sph_case(b, c);
  auto density = [&](uint32_t first, uint32_t count) {
    SphStepParams p = c.params;
    p.first = first;
    p.count = count;
    sph_density(b, p, {&s.sorted_pos, s.view(), &s.density, &s.pressure, &s.stats});
  };
  const uint32_t n = c.params.n;
  CHECK_THROWS_WITH_AS(density(n + 1, 0), doctest::Contains("invalid first = 65"), Error);
  CHECK_THROWS_WITH_AS(density(10, n - 9), doctest::Contains("invalid count = 55"), Error);
  CHECK_THROWS_WITH_AS(density(10, n - 9), doctest::Contains("at most n - first = 54"), Error);
  CHECK_NOTHROW(density(n, 0));
  CHECK_NOTHROW(density(n, kSphAllParticles));
  SphIntegrateParams ip;
  ip.n = n;
  ip.first = 3;
  ip.count = n;
  CHECK_THROWS_WITH_AS(sph_integrate(b, ip,
                                     {&s.sorted_pos, &s.sorted_vel, nullptr, &s.accel, &s.pos,
                                      &s.vel, nullptr, nullptr, &s.stats}),
                       doctest::Contains("invalid count"), Error);
}
