// The CPU reference's SPH row loops (engine/cpu/cpu_sph_rows.h): the AVX2 candidate test gives
// the very bits of the portable one (same neighbours, same order, same r^2), including points
// exactly at h, the particle itself, NaN positions and every row length mod 4.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "engine/cpu/cpu_sph_rows.h"

using namespace masav::cpu;

TEST_CASE("neighbors_row: the AVX2 path equals the portable one bit for bit") {
  if (!neighbors_row_uses_avx2())
    std::printf("note: this CPU has no AVX2; neighbors_row runs the portable path only\n");
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1.5, 1.5);
  const double h = 1.0, h2 = h * h;
  for (uint32_t count = 0; count < 70; ++count) {
    CAPTURE(count);
    std::vector<double> xs(count), ys(count), zs(count);
    for (uint32_t k = 0; k < count; ++k) xs[k] = u(rng), ys[k] = u(rng), zs[k] = u(rng);
    if (count > 3) xs[3] = 1.0, ys[3] = 0.0, zs[3] = 0.0;  // exactly at h: not a neighbour
    if (count > 5) ys[5] = std::nan("");
    const uint32_t first = 1000, self = first + count / 2;
    std::vector<uint32_t> a(count + 4, 0xdead), b(count + 4, 0xbeef);
    std::vector<double> ar(count + 4), br(count + 4);
    const uint32_t na = neighbors_row(xs.data(), ys.data(), zs.data(), first, count, 0.0, 0.0, 0.0,
                                      h2, self, a.data(), ar.data());
    const uint32_t nb = neighbors_row_portable(xs.data(), ys.data(), zs.data(), first, count, 0.0,
                                               0.0, 0.0, h2, self, b.data(), br.data());
    REQUIRE(na == nb);
    uint32_t want = 0;
    for (uint32_t k = 0; k < count; ++k) {
      const double r2 = (xs[k] * xs[k] + ys[k] * ys[k]) + zs[k] * zs[k];
      if (r2 < h2 && first + k != self) {
        REQUIRE(want < na);
        CHECK(a[want] == first + k);
        CHECK(ar[want] == r2);
        ++want;
      }
    }
    CHECK(want == na);
    for (uint32_t k = 0; k < na; ++k) {
      CHECK(a[k] == b[k]);
      CHECK(ar[k] == br[k]);
    }
  }
}

TEST_CASE("density_sum: (1 - r2/h2)^3 over the list, clamped at zero") {
  const std::vector<double> r2 = {0.0, 0.25, 0.5, 0.999999, 1.0, 0.75, 0.1};
  double want = 0;
  for (double v : r2) want += std::pow(std::max(0.0, 1.0 - v), 3);
  CHECK(density_sum(r2.data(), uint32_t(r2.size()), 1.0) == doctest::Approx(want).epsilon(1e-15));
  CHECK(density_sum(r2.data(), 0, 1.0) == 0.0);
}
