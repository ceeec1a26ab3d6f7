// Neighbour row masks (sph_density's optional output neighbor_rows, sph_forces' optional input),
// one test body each, on every backend. sph_forces over the masks must give what it gives
// without them: the same bits on the CPU reference and CUDA (the same neighbours summed in the
// same order), and on Vulkan within 1e-5 of the RMS acceleration, because its walk without masks
// sums in an order rotated within chunks of lanes (shaders/common/sph_coop.glsl) while the masked
// walk sums in ascending order; the neighbour counts exactly everywhere. The masks themselves
// are integers: each particle's neighbours within h, itself included, equal on every backend.
#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "engine/core/error.h"
#include "engine/kernels/sph_kernels.h"
#include "engine/sph/sph_kernel_calls.h"
#include "engine/util/error_metrics.h"
#include "tests/backend_fixture.h"
#include "tests/sph_fixture.h"

using namespace masav;

namespace {

// sph_density's outputs with the masks, and sph_forces' without and over them.
struct MaskedRun {
  std::vector<double> density;
  std::vector<uint32_t> rows;
  std::vector<Vec4d> full, masked;
};

MaskedRun run_masked(Backend& b, const test::SphCase& c) {
  test::SphBuffers s = test::upload_sph_case(b, c);
  sph_density(b, c.params,
              {&s.sorted_pos, s.view(), &s.density, &s.pressure, &s.stats, &s.neighbor_rows});
  auto forces = [&](const Buffer<uint32_t>* rows) {
    sph_forces(b, c.params,
               {&s.sorted_pos, &s.sorted_vel, &s.density, &s.pressure, s.view(), &s.accel, &s.stats,
                rows});
    return b.download(s.accel);
  };
  MaskedRun r;
  r.density = b.download(s.density);
  r.rows = b.download(s.neighbor_rows);
  r.full = forces(nullptr);
  r.masked = forces(&s.neighbor_rows);
  return r;
}

// Whether the backend's force walk without masks sums in the masked walk's order.
bool sums_in_row_order(const Backend& b) {
  return b.caps().backend != "vulkan";
}

void check_same_forces(const Backend& b, const MaskedRun& r) {
  REQUIRE(r.masked.size() == r.full.size());
  for (size_t i = 0; i < r.full.size(); ++i) REQUIRE(r.masked[i].w == r.full[i].w);
  if (sums_in_row_order(b)) {
    CHECK(std::memcmp(r.masked.data(), r.full.data(), r.full.size() * sizeof(Vec4d)) == 0);
  } else {
    // A particle whose walk a candidate cap stops before its own cell has no density, and it
    // and its neighbours get no finite acceleration: so in both walks.
    const auto all_got = xyz_components(r.masked), all_want = xyz_components(r.full);
    std::vector<double> got, want;
    for (size_t k = 0; k < all_want.size(); ++k) {
      REQUIRE(std::isfinite(all_got[k]) == std::isfinite(all_want[k]));
      if (!std::isfinite(all_want[k])) continue;
      got.push_back(all_got[k]);
      want.push_back(all_want[k]);
    }
    const ErrorStats e = compare(got, want, rms(want));
    INFO("masked vs full walk: " << describe(e));
    CHECK(e.max_rel < 1e-5);
  }
}

// Case `size` (make_sph_case's size and seed) with `extra` more particles crowding one cell,
// moving at up to `speed` times the spread of their positions.
test::SphCase crowded_case(uint32_t size, uint64_t seed, int extra, double speed) {
  test::SphCase c = test::make_sph_case(size, SphPressureModel::wcsph, seed);
  std::mt19937_64 rng(seed + 1);
  std::uniform_real_distribution<double> u(-0.25 * c.dx, 0.25 * c.dx);
  for (int k = 0; k < extra; ++k) {
    c.positions.push_back(
        {float(0.105 + u(rng)), float(0.105 + u(rng)), float(0.105 + u(rng)), 1.0f});
    c.velocities.push_back(
        {float(speed * u(rng)), float(speed * u(rng)), float(speed * u(rng)), 0.0f});
  }
  c.params.n = c.params.grid.n = uint32_t(c.positions.size());
  return c;
}

}  // namespace

TEST_CASE("sph_forces over neighbour row masks equals sph_forces walking every candidate") {
  Backend& b = test::backend();
  Backend& r = test::reference();
  test::for_each_model_and_walls(12, 41, [&](test::SphCase& c) {
    const MaskedRun got = run_masked(b, c);
    check_same_forces(b, got);
    const uint32_t n = c.params.n;
    // Each particle's bits are its neighbours within h and itself (no row here is too long).
    for (uint32_t i = 0; i < n; ++i)
      REQUIRE(test::row_mask_bits(got.rows, i, n) == got.full[i].w + 1);
    // The same bits as the CPU reference's (its own neighbour test, in double).
    CHECK(got.rows == run_masked(r, c).rows);
    // Recording the masks leaves the density as it was.
    test::SphBuffers s = test::upload_sph_case(b, c);
    sph_density(b, c.params, {&s.sorted_pos, s.view(), &s.density, &s.pressure, &s.stats});
    const auto plain = b.download(s.density);
    CHECK(std::memcmp(plain.data(), got.density.data(), plain.size() * sizeof(double)) == 0);
  });
}

// 60 more particles crowd one cell, so every row through it holds more candidates than a mask
// has bits: sph_density stores no bits for those rows and sph_forces walks them whole. With a
// small candidate cap, both kernels stop at the same row.
TEST_CASE("sph_forces over row masks walks a row too long for its mask whole") {
  Backend& b = test::backend();
  test::SphCase c = crowded_case(10, 43, 60, 10);
  for (const uint32_t cap : {8192u, 100u}) {
    CAPTURE(cap);
    c.params.max_candidates = cap;
    const MaskedRun got = run_masked(b, c);
    check_same_forces(b, got);
    // The rows the kernels walk, from the shared walk over the grid's cell ranges.
    test::SphBuffers s = test::upload_sph_case(b, c);
    const auto cells = b.download(s.grid.sorted_cells);
    const auto start = b.download(s.grid.cell_start), end = b.download(s.grid.cell_end);
    const SphStepParams& p = c.params;
    const uint32_t dims[3] = {p.grid.dims.x, p.grid.dims.y, p.grid.dims.z};
    uint32_t long_rows = 0;
    for (uint32_t i = 0; i < p.n; ++i) {
      bool overflow = false;
      sph::walk_rows(cells[i], dims, start.data(), end.data(), p.max_candidates, overflow,
                     [&](uint32_t row, uint32_t first, uint32_t last) {
                       const uint64_t bits =
                           sph::load_row_mask(sph::row_masks(got.rows.data(), i, p.n), row);
                       const uint32_t lo = uint32_t(bits), hi = uint32_t(bits >> 32);
                       const uint32_t count = last - first;
                       if (count > kSphRowMaskBits) {
                         ++long_rows;
                         REQUIRE((lo | hi) == 0);
                       } else if (count <= 32) {  // no bit past the row
                         REQUIRE(hi == 0);
                         REQUIRE((count == 32 || lo >> count == 0));
                       } else {
                         REQUIRE((count == 64 || hi >> (count - 32) == 0));
                       }
                     });
    }
    CHECK(long_rows > 0);
  }
}

// 30 more particles crowd one cell, so rows through it hold 33 to 64 candidates: their masks
// fill the second word, from bits that a cooperative walk's chunks carry across the words.
TEST_CASE("sph_density's masks of rows longer than one word equal the CPU reference's") {
  Backend& b = test::backend();
  Backend& r = test::reference();
  const test::SphCase c = crowded_case(10, 45, 30, 0);
  const MaskedRun got = run_masked(b, c);
  CHECK(got.rows == run_masked(r, c).rows);
  check_same_forces(b, got);
  const uint32_t n = c.params.n;
  uint32_t high_words = 0;
  for (uint32_t row = 0; row < 9; ++row)
    for (uint32_t i = 0; i < n; ++i)
      high_words += sph::load_row_mask(sph::row_masks(got.rows.data(), i, n), row) >> 32 != 0;
  CHECK(high_words > 0);
}

TEST_CASE("sph kernels reject a neighbor_rows buffer too small, naming it") {
  Backend& b = test::backend();
  const test::SphCase c = test::make_sph_case(4, SphPressureModel::wcsph, 1);
  test::SphBuffers s = test::upload_sph_case(b, c);
  auto rows = b.create<uint32_t>(size_t(kSphRowMaskWords) * c.params.n - 1, "short rows");
  CHECK_THROWS_WITH_AS(
      sph_density(b, c.params, {&s.sorted_pos, s.view(), &s.density, &s.pressure, &s.stats, &rows}),
      doctest::Contains("neighbor_rows size"), Error);
  CHECK_THROWS_WITH_AS(sph_forces(b, c.params,
                                  {&s.sorted_pos, &s.sorted_vel, &s.density, &s.pressure, s.view(),
                                   &s.accel, &s.stats, &rows}),
                       doctest::Contains("neighbor_rows size"), Error);
}
