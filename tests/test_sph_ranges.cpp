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
#include "engine/sph/sph_kernel_calls.h"
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

}  // namespace

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
    check_range(
        n, span,
        [&](size_t i) {
          return std::pair{d[i], rho[i]};
        },
        "density");
    check_range(
        n, span,
        [&](size_t i) {
          return std::pair{q[i], pr[i]};
        },
        "pressure");

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
