// RK4's reach masks (SphReach, engine/kernels/sph_kernel_params.h), one test body each, on every
// backend. sph_density records which candidates lie within the reach radius (the grid's cell
// size, h + skin) at the step's first positions; at positions moved by at most skin / 2 it then
// walks only those. The walk must find what the whole walk over the 27 cells finds: the same
// neighbour row masks and counts everywhere, and the same density bit for bit on the CPU
// reference and CUDA (the same terms in the same order, less the zeros beyond h); on Vulkan within
// 1e-6, because its whole walk sums in an order rotated within chunks of lanes
// (shaders/common/sph_coop.glsl) while the reach walk sums in ascending order.
#include <doctest/doctest.h>

#include <bit>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "engine/core/error.h"
#include "engine/sph/sph_kernel_calls.h"
#include "engine/util/error_metrics.h"
#include "tests/backend_fixture.h"
#include "tests/sph_fixture.h"
#include "tests/sph_state_compare.h"
#include "tests/sph_switch_run.h"

using namespace masav;

namespace {

constexpr double kSkin = 0.25;  // of h, as a generous rk4_skin

// make_sph_case on RK4's grid: cells of h (1 + skin), the reach radius their size.
test::SphCase reach_case(uint32_t side, SphPressureModel model, uint64_t seed, bool walls,
                         int crowd = 0) {
  test::SphCase c = test::make_sph_case(side, model, seed);
  std::mt19937_64 rng(seed + 7);
  std::uniform_real_distribution<double> u(-0.25 * c.dx, 0.25 * c.dx);
  for (int k = 0; k < crowd; ++k) {  // crowding one cell: rows too long for a mask
    c.positions.push_back(
        {float(0.105 + u(rng)), float(0.105 + u(rng)), float(0.105 + u(rng)), 1.0f});
    c.velocities.push_back({0.0f, 0.0f, 0.0f, 0.0f});
  }
  test::with_walls(c, walls);
  SphStepParams& p = c.params;
  p.n = uint32_t(c.positions.size());
  const float cell = std::nextafter(float(p.h * (1.0 + kSkin)), 1.0f);
  const uint32_t cells = uint32_t(std::ceil((0.1 + side * c.dx) / double(cell)));
  p.grid = make_grid_params({0, 0, 0}, cell, {cells, cells, cells}, p.n);
  p.reach_radius = double(cell);
  return c;
}

struct ReachRun {
  std::vector<uint32_t> reach;                  // recorded at the sorted positions
  std::vector<double> plain_density, recorded;  // there, without and with recording
  std::vector<uint32_t> plain_rows;             // there, within h
  std::vector<double> whole, walked;            // at the moved positions
  std::vector<uint32_t> whole_rows, walked_rows, whole_stats, walked_stats;
};

ReachRun run_reach(Backend& b, const test::SphCase& c) {
  const uint32_t n = c.params.n;
  test::SphBuffers s = test::upload_sph_case(b, c);
  auto reach = b.create<uint32_t>(size_t(kSphRowMaskWords) * n, "test reach rows");
  auto density = [&](SphReach mode, std::vector<double>& rho, std::vector<uint32_t>* rows,
                     std::vector<uint32_t>* stats) {
    SphStepParams p = c.params;
    p.reach = mode;
    b.fill(s.stats, 0u);
    sph_density(b, p,
                {&s.sorted_pos, s.view(), &s.density, &s.pressure, &s.stats, &s.neighbor_rows,
                 mode == SphReach::none ? nullptr : &reach});
    rho = b.download(s.density);
    if (rows) *rows = b.download(s.neighbor_rows);
    if (stats) *stats = b.download(s.stats);
  };
  ReachRun r;
  density(SphReach::none, r.plain_density, &r.plain_rows, nullptr);
  density(SphReach::record, r.recorded, nullptr, nullptr);
  r.reach = b.download(reach);
  // Each sorted particle moves by at most skin / 2 (seeded by its sorted index: the same moves
  // on every backend, whose sorted orders are the same), in fp32 as the backends hold them.
  std::vector<Vec4d> pos = b.download(s.sorted_pos);
  std::vector<Vec4f> moved(pos.size());
  const double most = 0.5 * kSkin * c.params.h / std::sqrt(3.0) * 0.999;
  std::mt19937_64 rng(99);
  std::uniform_real_distribution<double> u(-most, most);
  for (size_t i = 0; i < pos.size(); ++i)
    moved[i] = {float(pos[i].x + u(rng)), float(pos[i].y + u(rng)), float(pos[i].z + u(rng)),
                float(pos[i].w)};
  b.upload(s.sorted_pos, std::span<const Vec4f>(moved));
  density(SphReach::none, r.whole, &r.whole_rows, &r.whole_stats);
  density(SphReach::walk, r.walked, &r.walked_rows, &r.walked_stats);
  return r;
}

uint32_t popcount_row(const std::vector<uint32_t>& rows, uint32_t i, uint32_t n, uint32_t row) {
  return uint32_t(std::popcount(sph::load_row_mask(sph::row_masks(rows.data(), i, n), row)));
}

void check_reach_run(const Backend& b, const test::SphCase& c, const ReachRun& r) {
  const uint32_t n = c.params.n;
  // Recording the reach masks leaves the density as it was, and they hold every neighbour
  // within h (and more: h + skin reaches further).
  CHECK(std::memcmp(r.recorded.data(), r.plain_density.data(), n * sizeof(double)) == 0);
  uint64_t reach_bits = 0, h_bits = 0;
  for (uint32_t i = 0; i < n; ++i)
    for (uint32_t row = 0; row < 9; ++row) {
      const auto masks = sph::row_masks(r.plain_rows.data(), i, n);
      const auto reaches = sph::row_masks(r.reach.data(), i, n);
      const uint64_t within = sph::load_row_mask(masks, row);
      REQUIRE((within & ~sph::load_row_mask(reaches, row)) == 0);
      h_bits += popcount_row(r.plain_rows, i, n, row);
      reach_bits += popcount_row(r.reach, i, n, row);
    }
  CHECK(reach_bits > h_bits);
  // At the moved positions the walk over the reach masks finds what the whole walk finds.
  CHECK(r.walked_rows == r.whole_rows);
  CHECK(r.walked_stats[kSphStatMaxNeighbors] == r.whole_stats[kSphStatMaxNeighbors]);
  CHECK(r.walked_stats[kSphStatMaxCandidates] == r.whole_stats[kSphStatMaxCandidates]);
  if (b.caps().backend != "vulkan") {
    CHECK(std::memcmp(r.walked.data(), r.whole.data(), n * sizeof(double)) == 0);
  } else {
    const ErrorStats e = compare(r.walked, r.whole, rms(r.whole));
    INFO("reach walk vs whole walk: " << describe(e));
    CHECK(e.max_rel < 1e-6);
  }
}

}  // namespace

TEST_CASE("sph_density over reach masks finds what the whole walk finds, skin / 2 later") {
  Backend& b = test::backend();
  Backend& ref = test::reference();
  for (const bool walls : {false, true})
    for (SphPressureModel model : {SphPressureModel::wcsph, SphPressureModel::thesis}) {
      const std::string name = to_string(model);
      CAPTURE(name);
      CAPTURE(walls);
      const test::SphCase c = reach_case(12, model, 51, walls);
      const ReachRun got = run_reach(b, c);
      check_reach_run(b, c, got);
      // The reach masks are integers: the same as the CPU reference's (its own test, in double).
      CHECK(got.reach == run_reach(ref, c).reach);
    }
}

// 70 more particles crowd one cell, so every row through it holds more candidates than a mask
// has bits: the record stores no bits for those rows and the reach walk walks them whole.
TEST_CASE("sph_density's reach walk walks a row too long for its mask whole") {
  Backend& b = test::backend();
  const test::SphCase c = reach_case(10, SphPressureModel::wcsph, 53, true, 70);
  const ReachRun got = run_reach(b, c);
  check_reach_run(b, c, got);
  const uint32_t n = c.params.n;
  uint32_t empty_rows = 0;
  for (uint32_t i = 0; i < n; ++i)
    for (uint32_t row = 0; row < 9; ++row) empty_rows += popcount_row(got.reach, i, n, row) == 0;
  CHECK(empty_rows > 0);
  CHECK(got.whole_stats[kSphStatMaxCandidates] > kSphRowMaskBits);
}

TEST_CASE("sph_density rejects reach masks it cannot use, naming the field") {
  Backend& b = test::backend();
  const test::SphCase c = reach_case(4, SphPressureModel::wcsph, 1, false);
  test::SphBuffers s = test::upload_sph_case(b, c);
  auto reach = b.create<uint32_t>(size_t(kSphRowMaskWords) * c.params.n, "reach");
  auto call = [&](const SphStepParams& p, Buffer<uint32_t>* rows) {
    sph_density(
        b, p, {&s.sorted_pos, s.view(), &s.density, &s.pressure, &s.stats, &s.neighbor_rows, rows});
  };
  SphStepParams p = c.params;
  p.reach = SphReach::walk;
  CHECK_THROWS_WITH_AS(call(p, nullptr), doctest::Contains("reach_rows"), Error);
  CHECK_THROWS_WITH_AS(call(p, &s.neighbor_rows), doctest::Contains("a buffer of its own"), Error);
  auto short_rows = b.create<uint32_t>(size_t(kSphRowMaskWords) * c.params.n - 1, "short");
  CHECK_THROWS_WITH_AS(call(p, &short_rows), doctest::Contains("reach_rows size"), Error);
  p.reach = SphReach::record;
  p.reach_radius = double(p.grid.cell_size) * 1.01;  // beyond the 27 cells
  CHECK_THROWS_WITH_AS(call(p, &reach), doctest::Contains("reach_radius"), Error);
  p.reach_radius = 0.5 * p.h;
  CHECK_THROWS_WITH_AS(call(p, &reach), doctest::Contains("[h, grid cell_size]"), Error);
  p.reach_radius = std::nan("");
  CHECK_THROWS_WITH_AS(call(p, &reach), doctest::Contains("reach_radius"), Error);
  p.reach = SphReach(7);
  CHECK_THROWS_WITH_AS(call(p, &reach), doctest::Contains("none (0), record (1) or walk (2)"),
                       Error);
}

namespace {

// An RK4 dam break over the reach masks or (drop) the inflated cells; whether the simulation
// kept the masks.
SphState run_rk4(bool drop, bool& kept) {
  test::SwitchRun r = test::run_dam_break_on(test::backend(), SphIntegrator::rk4, drop);
  kept = r.reach_masks;
  return std::move(r.state);
}

}  // namespace

TEST_CASE("[sph-physics] RK4 over reach masks keeps the trajectory of the whole walks") {
  bool with = false, without = true;
  const SphState on = run_rk4(false, with), off = run_rk4(true, without);
  CHECK(with);
  CHECK_FALSE(without);
  if (test::backend().caps().backend != "vulkan") {
    CHECK(test::same_state(on, off));
  } else {
    // Vulkan's sums differ in order (see the top): the trajectories agree to rounding grown over
    // 24 steps (lavapipe: 4.2e-7 m), far below the particle spacing.
    REQUIRE(on.positions.size() == off.positions.size());
    double most = 0;
    for (size_t i = 0; i < on.positions.size(); ++i) {
      const Vec4d &p = on.positions[i], &q = off.positions[i];
      most = std::max({most, std::abs(p.x - q.x), std::abs(p.y - q.y), std::abs(p.z - q.z)});
    }
    INFO("largest position difference " << most << " m");
    CHECK(most < 1e-5);
  }
}
