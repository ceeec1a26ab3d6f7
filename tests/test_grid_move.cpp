// grid_rank_and_move, the counting build's rank pass moving each point's data into cell order:
// equal bit for bit to the rank pass followed by three gathers, on every backend and against the
// CPU reference; its bad inputs fail with messages that name it; its loop stays in budget.
#include <doctest/doctest.h>

#include <random>
#include <vector>

#include "engine/core/error.h"
#include "engine/grid/hash_grid.h"
#include "engine/kernels/kernel_checks.h"
#include "tests/backend_fixture.h"
#include "tests/loop_limit.h"

using namespace masav;

namespace {

struct Moved {
  std::vector<uint32_t> sorted_cells, sorted_index, start, end, ids;
  std::vector<Vec4d> positions, velocities;
};

// n random points in a box of dims cells of size `cell`, velocities and ids derived from them;
// moved by the rank pass (`moving`) or by a counting build and three reorders.
Moved sort_points(Backend& b, uint32_t n, UVec3 dims, float cell, bool moving, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<Vec4f> pos(n), vel(n);
  std::vector<uint32_t> ids(n);
  for (uint32_t i = 0; i < n; ++i) {
    pos[i] = {u(rng) * dims.x * cell, u(rng) * dims.y * cell, u(rng) * dims.z * cell, 1.0f};
    vel[i] = {u(rng) - 0.5f, u(rng), -u(rng), 0.0f};
    ids[i] = n - 1 - i;
  }
  const GridParams gp = make_grid_params({0, 0, 0}, cell, dims, n);
  HashGrid g = make_hash_grid(b, gp, n);
  auto x = b.create<Real4>(n, "x"), xs = b.create<Real4>(n, "x sorted");
  auto v = b.create<Real4>(n, "v"), vs = b.create<Real4>(n, "v sorted");
  auto id = b.create<uint32_t>(n, "ids"), ids_s = b.create<uint32_t>(n, "ids sorted");
  b.upload(x, pos);
  b.upload(v, vel);
  b.upload(id, ids);
  const uint32_t cap = max_walk_candidates(b);
  if (moving) {
    build_hash_grid_moving(b, g, x, cap, MovedArrays{&xs, &v, &vs, &id, &ids_s});
  } else {
    build_hash_grid(b, g, x, {GridBuild::counting, cap});
    reorder(b, g, x.impl(), xs.impl());
    reorder(b, g, v.impl(), vs.impl());
    reorder(b, g, id.impl(), ids_s.impl());
  }
  return {b.download(g.sorted_cells),
          b.download(g.sorted_index),
          b.download(g.cell_start),
          b.download(g.cell_end),
          b.download(ids_s),
          b.download(xs),
          b.download(vs)};
}

// n points at one spot of a one-cell grid, with every array grid_rank_and_move moves.
struct OneCell {
  HashGrid g;
  Buffer<Real4> x, xs, v, vs;
  Buffer<uint32_t> id, ids_s;
  OneCell(Backend& b, uint32_t n)
      : g(make_hash_grid(b, make_grid_params({0, 0, 0}, 1.0f, {1, 1, 1}, n), n)),
        x(b.create<Real4>(n, "x")),
        xs(b.create<Real4>(n, "x sorted")),
        v(b.create<Real4>(n, "v")),
        vs(b.create<Real4>(n, "v sorted")),
        id(b.create<uint32_t>(n, "ids")),
        ids_s(b.create<uint32_t>(n, "ids sorted")) {
    b.upload(x, std::vector<Vec4f>(n, Vec4f{0.5f, 0.5f, 0.5f, 1.0f}));
  }
  MovedArrays moved() { return {&xs, &v, &vs, &id, &ids_s}; }
};

bool same(const std::vector<Vec4d>& a, const std::vector<Vec4d>& b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i)
    if (a[i].x != b[i].x || a[i].y != b[i].y || a[i].z != b[i].z || a[i].w != b[i].w) return false;
  return true;
}

}  // namespace

TEST_CASE("grid_rank_and_move equals the rank pass and three gathers, bit for bit") {
  Backend& b = test::backend();
  Backend& r = test::reference();
  struct Case {
    uint32_t n;
    UVec3 dims;
    float cell;
  };
  uint32_t seed = 3;
  for (const Case& c : {Case{1, {2, 2, 2}, 0.5f}, Case{1000, {8, 5, 3}, 0.25f},
                        Case{20000, {32, 32, 32}, 0.1f}, Case{5000, {1, 1, 1}, 1.0f}}) {
    CAPTURE(c.n);
    const Moved got = sort_points(b, c.n, c.dims, c.cell, true, seed);
    const Moved two = sort_points(b, c.n, c.dims, c.cell, false, seed);
    const Moved ref = sort_points(r, c.n, c.dims, c.cell, true, seed);
    ++seed;
    CHECK(got.sorted_cells == two.sorted_cells);
    CHECK(got.sorted_index == two.sorted_index);
    CHECK(got.start == two.start);
    CHECK(got.end == two.end);
    CHECK(got.ids == two.ids);
    CHECK(same(got.positions, two.positions));
    CHECK(same(got.velocities, two.velocities));
    // Against the CPU reference: the same order, and the same fp32 data moved.
    CHECK(got.sorted_index == ref.sorted_index);
    CHECK(got.ids == ref.ids);
  }
}

TEST_CASE("grid_rank_and_move's bad inputs fail with messages that name it") {
  Backend& b = test::backend();
  const uint32_t n = 64;
  OneCell o(b, n);
  auto& [g, x, xs, v, vs, id, ids_s] = o;
  // Every point in one cell, one more than the cap allows.
  CHECK_THROWS_WITH_AS(
      {
        build_hash_grid_moving(b, g, x, n - 1, o.moved());
        b.finish();
      },
      doctest::Contains("grid_rank_and_move: cell 0 holds more than max_per_cell = 63"), Error);
  // In place would overwrite points that have not moved yet.
  CHECK_THROWS_WITH_AS(build_hash_grid_moving(b, g, x, n, MovedArrays{&xs, &v, &v, &id, &ids_s}),
                       doctest::Contains("same buffer"), Error);
  CHECK_THROWS_WITH_AS(build_hash_grid_moving(b, g, x, n, MovedArrays{&xs, &v, &vs, &id, nullptr}),
                       doctest::Contains("every moved array"), Error);
  auto short_v = b.create<Real4>(n - 1, "short v");
  CHECK_THROWS_WITH_AS(
      build_hash_grid_moving(b, g, x, n, MovedArrays{&xs, &short_v, &vs, &id, &ids_s}),
      doctest::Contains("n = 64"), Error);
  // After the errors the grid still builds.
  build_hash_grid_moving(b, g, x, n, o.moved());
  CHECK(b.download(g.cell_end)[0] == n);
}

LOOP_LIMIT_CASE("grid_rank_and_move loops over its point's cell", KernelId::grid_rank_and_move) {
  Backend& b = test::loop_counter();
  // The worst case: every point in one cell.
  const uint32_t n = 4000;
  OneCell o(b, n);
  auto& [g, x, xs, v, vs, id, ids_s] = o;
  build_hash_grid_moving(b, g, x, n, o.moved());
  CHECK(test::ticks_of(b) == n);
  // The validated maximum of max_per_cell keeps the worst invocation under the limit.
  CHECK(max_walk_candidates(b) + 1 < b.caps().max_loop_iterations);
  CHECK_THROWS_AS(build_hash_grid_moving(b, g, x, max_walk_candidates(b) + 1, o.moved()), Error);
  CHECK(test::ticks_of(b) == 0);  // refused before any pass ran
}
