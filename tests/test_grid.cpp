// Hash grid: cells, sorted (cell, index), cell ranges and reorder equal the CPU reference bit for
// bit and a brute-force grouping; the 27-cell neighbour count equals an O(n^2) search; the passes
// of the counting sort by cell (counts, offsets, scatter, rank) equal host computations, and the
// counting build equals the radix build bit for bit, build after build.
#include <doctest/doctest.h>

#include <algorithm>
#include <cstring>
#include <map>
#include <numeric>
#include <random>
#include <vector>

#include "engine/core/error.h"
#include "engine/grid/hash_grid.h"
#include "engine/kernels/grid_cell.h"
#include "engine/kernels/kernel_checks.h"
#include "tests/backend_fixture.h"
#include "tests/loop_limit.h"

using namespace masav;

namespace {

struct Scene {
  GridParams params;
  std::vector<Vec4f> points;
};

// Points in a box, some outside it (clamped), some exactly on cell faces.
Scene make_scene(uint32_t n, UVec3 dims, float cell, uint64_t seed, float spill = 0.1f) {
  Scene s;
  s.params = make_grid_params({-1.25f, 0.5f, 2.0f}, cell, dims, n);
  std::mt19937_64 rng(seed);
  const Vec3f size{dims.x * cell, dims.y * cell, dims.z * cell};
  std::uniform_real_distribution<float> u(-spill, 1.0f + spill);
  for (uint32_t i = 0; i < n; ++i) {
    Vec4f p{s.params.origin.x + u(rng) * size.x, s.params.origin.y + u(rng) * size.y,
            s.params.origin.z + u(rng) * size.z, float(i)};
    if (i % 17 == 0) p.x = s.params.origin.x + float(rng() % (dims.x + 1)) * cell;  // on a face
    s.points.push_back(p);
  }
  return s;
}

// The grids both builds are checked on: empty, one point, all points in one cell, mostly empty
// cells, a large spread.
struct GridCase {
  uint32_t n;
  UVec3 dims;
  float cell;
};
constexpr GridCase kGridCases[] = {{0, {4, 4, 4}, 0.5f},           {1, {4, 4, 4}, 0.5f},
                                   {2, {1, 1, 1}, 3.0f},           {1000, {13, 7, 29}, 0.1f},
                                   {100003, {64, 32, 48}, 0.03f},  {5000, {1, 1, 1}, 1.0f},
                                   {20000, {512, 256, 64}, 0.001f}};

struct GridResult {
  std::vector<uint32_t> cells, index, start, end;
};

GridResult download(Backend& b, const HashGrid& g) {
  return {b.download(g.sorted_cells), b.download(g.sorted_index), b.download(g.cell_start),
          b.download(g.cell_end)};
}

GridResult build_on(Backend& b, const Scene& s, HashGrid* keep = nullptr,
                    Buffer<Real4>* pos_out = nullptr, const GridBuildOptions& build = {}) {
  auto pos = b.create<Real4>(s.points.size(), "positions");
  b.upload(pos, s.points);
  HashGrid g = make_hash_grid(b, s.params, s.points.size());
  build_hash_grid(b, g, pos, build);
  GridResult r = download(b, g);
  if (keep) *keep = std::move(g);
  if (pos_out) *pos_out = std::move(pos);
  return r;
}

uint32_t host_cell(const GridParams& g, const Vec4f& p) {
  const float origin[3] = {g.origin.x, g.origin.y, g.origin.z};
  const uint32_t dims[3] = {g.dims.x, g.dims.y, g.dims.z};
  const auto c = grid::point_cell(p.x, p.y, p.z, origin, g.inv_cell, dims);
  return grid::cell_id(c.x, c.y, c.z, dims[1], dims[2]);
}

}  // namespace

TEST_CASE("hash grid equals the CPU reference and a brute-force grouping") {
  uint64_t seed = 11;
  for (const auto& c : kGridCases) {
    CAPTURE(c.n);
    CAPTURE(c.dims.x);
    const Scene s = make_scene(c.n, c.dims, c.cell, seed++);
    const GridResult got = build_on(test::backend(), s);
    const GridResult ref = build_on(test::reference(), s);
    CHECK(got.cells == ref.cells);
    CHECK(got.index == ref.index);
    CHECK(got.start == ref.start);
    CHECK(got.end == ref.end);

    // Brute force: group indices by cell in index order.
    std::map<uint32_t, std::vector<uint32_t>> groups;
    for (uint32_t i = 0; i < c.n; ++i) groups[host_cell(s.params, s.points[i])].push_back(i);
    std::vector<uint32_t> cells, index;
    for (const auto& [cell, members] : groups)
      for (uint32_t i : members) cells.push_back(cell), index.push_back(i);
    CHECK(got.cells == cells);
    CHECK(got.index == index);
    size_t nonempty = 0;
    for (size_t cell = 0; cell < got.start.size(); ++cell) {
      const auto it = groups.find(uint32_t(cell));
      if (it == groups.end()) {
        CHECK(got.start[cell] == got.end[cell]);
        continue;
      }
      ++nonempty;
      REQUIRE(got.end[cell] - got.start[cell] == it->second.size());
      CHECK(got.index[got.start[cell]] == it->second.front());
    }
    CHECK(nonempty == groups.size());
  }
}

TEST_CASE("reorder gathers per-point arrays into cell order, exactly") {
  Backend& b = test::backend();
  Backend& r = test::reference();
  const Scene s = make_scene(30011, {20, 20, 20}, 0.05f, 5);
  HashGrid gb, gr;
  Buffer<Real4> pb, pr;
  build_on(b, s, &gb, &pb);
  build_on(r, s, &gr, &pr);
  auto sorted_b = b.create<Real4>(s.points.size(), "sorted positions");
  auto sorted_r = r.create<Real4>(s.points.size(), "sorted positions");
  reorder(b, gb, pb.impl(), sorted_b.impl());
  reorder(r, gr, pr.impl(), sorted_r.impl());
  const auto got = b.download_f32(sorted_b), want = r.download_f32(sorted_r);
  REQUIRE(got.size() == want.size());
  CHECK(std::memcmp(got.data(), want.data(), got.size() * sizeof(Vec4f)) == 0);
  const auto index = b.download(gb.sorted_index);
  for (size_t i = 0; i < got.size(); i += 97) CHECK(got[i].w == s.points[index[i]].w);

  // 32-bit payloads too.
  std::vector<uint32_t> ids(s.points.size());
  for (size_t i = 0; i < ids.size(); ++i) ids[i] = uint32_t(i * 2654435761u);
  auto src = b.create<uint32_t>(ids.size(), "ids");
  auto dst = b.create<uint32_t>(ids.size(), "ids sorted");
  b.upload(src, ids);
  b.gather({uint32_t(ids.size())}, gb.sorted_index, src.impl(), dst.impl());
  const auto moved = b.download(dst);
  for (size_t i = 0; i < moved.size(); ++i) REQUIRE(moved[i] == ids[index[i]]);
}

TEST_CASE("27-cell neighbour counts equal an O(n^2) search") {
  Backend& b = test::backend();
  const float cell = 0.1f;
  Scene s = make_scene(3001, {9, 8, 7}, cell, 77, 0.0f);
  HashGrid g;
  Buffer<Real4> pos;
  build_on(b, s, &g, &pos);
  auto sorted = b.create<Real4>(s.points.size(), "sorted");
  reorder(b, g, pos.impl(), sorted.impl());
  auto counts = b.create<uint32_t>(s.points.size(), "counts");
  for (float radius : {0.1f, 0.05f, 0.0137f}) {
    CAPTURE(radius);
    const NeighborParams np = make_neighbor_params(s.params, radius);
    b.grid_count_neighbors(np, sorted, g.cell_start, g.cell_end, counts);
    const auto got = b.download(counts);
    const auto sp = b.download_f32(sorted);
    size_t mismatches = 0;
    for (size_t i = 0; i < sp.size(); ++i) {
      uint32_t want = 0;
      for (size_t j = 0; j < sp.size(); ++j)
        want += grid::distance2(sp[i].x, sp[i].y, sp[i].z, sp[j].x, sp[j].y, sp[j].z) <= np.radius2;
      mismatches += got[i] != want;
    }
    CHECK(mismatches == 0);
  }
}

TEST_CASE("neighbour search over its candidate cap and gathers past the source are errors") {
  Backend& b = test::backend();
  Scene s = make_scene(3000, {1, 1, 1}, 1.0f, 3, 0.0f);  // all in one cell
  HashGrid g;
  Buffer<Real4> pos;
  build_on(b, s, &g, &pos);
  auto counts = b.create<uint32_t>(s.points.size(), "counts");
  NeighborParams np = make_neighbor_params(s.params, 1.0f);
  np.max_candidates = 2999;
  CHECK_THROWS_WITH_AS(
      {
        b.grid_count_neighbors(np, pos, g.cell_start, g.cell_end, counts);
        b.finish();
      },
      doctest::Contains("more than 2999 candidates"), Error);
  np.max_candidates = 3000;  // exactly enough: every point is a candidate of every other
  b.grid_count_neighbors(np, pos, g.cell_start, g.cell_end, counts);
  const auto p = b.download_f32(pos);
  uint32_t within = 0;
  for (const auto& q : p) within += grid::distance2(p[0].x, p[0].y, p[0].z, q.x, q.y, q.z) <= 1.0f;
  CHECK(b.download(counts)[0] == within);

  auto order = b.create<uint32_t>(4, "order");
  b.upload(order, std::vector<uint32_t>{0, 1, 99, 2});
  auto src = b.create<uint32_t>(3, "src");
  auto dst = b.create<uint32_t>(4, "dst");
  b.upload(src, std::vector<uint32_t>{5, 6, 7});
  CHECK_THROWS_WITH_AS(
      {
        b.gather({4}, order, src.impl(), dst.impl());
        b.finish();
      },
      doctest::Contains("order[2]"), Error);
}

TEST_CASE("grid parameters out of range are rejected, naming the field") {
  Backend& b = test::backend();
  auto pos = b.create<Real4>(4, "pos");
  auto cells = b.create<uint32_t>(4, "cells");
  auto idx = b.create<uint32_t>(4, "idx");
  GridParams g = make_grid_params({0, 0, 0}, 0.0f, {4, 4, 4}, 4);
  CHECK_THROWS_WITH_AS(b.grid_assign_cells(g, pos, cells, idx), doctest::Contains("cell_size"),
                       Error);
  g = make_grid_params({0, 0, 0}, 1.0f, {0, 4, 4}, 4);
  CHECK_THROWS_WITH_AS(b.grid_assign_cells(g, pos, cells, idx), doctest::Contains("dims"), Error);
  g = make_grid_params({0, 0, 0}, 1.0f, {4, 4, 4}, 5);
  CHECK_THROWS_WITH_AS(b.grid_assign_cells(g, pos, cells, idx), doctest::Contains("n = 5"), Error);
  g = make_grid_params({NAN, 0, 0}, 1.0f, {4, 4, 4}, 4);
  CHECK_THROWS_WITH_AS(b.grid_assign_cells(g, pos, cells, idx), doctest::Contains("origin"), Error);
  const GridParams ok = make_grid_params({0, 0, 0}, 1.0f, {4, 4, 4}, 4);
  auto start = b.create<uint32_t>(64, "start");
  auto end = b.create<uint32_t>(64, "end");
  CHECK_THROWS_WITH_AS(
      b.grid_count_neighbors(make_neighbor_params(ok, 1.5f), pos, start, end, cells),
      doctest::Contains("radius"), Error);
}

// Counts of `n` cell ids counted onto `start` on backend b.
std::vector<uint32_t> count_cells_on(Backend& b, const std::vector<uint32_t>& ids,
                                     const std::vector<uint32_t>& start, uint32_t n) {
  auto cells = b.create<uint32_t>(ids.size(), "cells");
  auto counts = b.create<uint32_t>(start.size(), "counts");
  b.upload(cells, ids);
  b.upload(counts, start);
  b.grid_count_cells({n, uint32_t(start.size())}, cells, counts);
  return b.download(counts);
}

TEST_CASE("grid_count_cells adds each cell's count, equal to a host count and the CPU reference") {
  std::mt19937 rng(41);
  for (const uint32_t n : {0u, 1u, 1000u, 300007u})
    for (const uint32_t cell_count : {1u, 7u, 4096u, 1u << 20}) {
      CAPTURE(n);
      CAPTURE(cell_count);
      // A third of the ids in one hot cell (contended atomics), the rest spread; the table
      // starts non-zero, since the kernel adds; a few ids past n must not count.
      std::vector<uint32_t> ids(n + 5), start(cell_count), want(cell_count);
      for (auto& id : ids) id = rng() % 3 == 0 ? cell_count / 2 : rng() % cell_count;
      for (uint32_t c = 0; c < cell_count; ++c) start[c] = want[c] = c % 5;
      for (uint32_t i = 0; i < n; ++i) ++want[ids[i]];
      const auto got = count_cells_on(test::backend(), ids, start, n);
      CHECK(got == want);
      CHECK(got == count_cells_on(test::reference(), ids, start, n));
    }
}

TEST_CASE("grid_count_cells of a hash grid's cells equals its cell ranges") {
  Backend& b = test::backend();
  const Scene s = make_scene(50000, {40, 24, 32}, 0.05f, 9);
  HashGrid g;
  const GridResult r = build_on(b, s, &g);
  const uint32_t cells = uint32_t(grid_cell_count(s.params));
  auto counts = b.create<uint32_t>(cells, "counts");
  b.fill(counts, 0u);
  b.grid_count_cells({uint32_t(s.points.size()), cells}, g.sorted_cells, counts);
  const auto got = b.download(counts);
  uint32_t mismatches = 0;
  for (uint32_t c = 0; c < cells; ++c) mismatches += got[c] != r.end[c] - r.start[c];
  CHECK(mismatches == 0);
}

TEST_CASE("grid_count_cells rejects cells past the table and sizes past its buffers") {
  Backend& b = test::backend();
  auto cells = b.create<uint32_t>(4, "cells");
  auto counts = b.create<uint32_t>(8, "counts");
  b.upload(cells, std::vector<uint32_t>{0, 7, 8, 3});
  b.fill(counts, 0u);
  CHECK_THROWS_WITH_AS(
      {
        b.grid_count_cells({4, 8}, cells, counts);
        b.finish();
      },
      doctest::Contains("cells[2] is not below cell_count 8"), Error);
  CHECK_THROWS_WITH_AS(b.grid_count_cells({4, 9}, cells, counts), doctest::Contains("cell_count"),
                       Error);
  CHECK_THROWS_WITH_AS(b.grid_count_cells({4, 0}, cells, counts), doctest::Contains("cell_count"),
                       Error);
  CHECK_THROWS_WITH_AS(b.grid_count_cells({5, 8}, cells, counts), doctest::Contains("n"), Error);
  // The cells before the bad one may have counted; the first two alone count exactly.
  b.fill(counts, 0u);
  b.grid_count_cells({2, 8}, cells, counts);
  CHECK(b.download(counts) == std::vector<uint32_t>{1, 0, 0, 0, 0, 0, 0, 1});
}

// grid_assign_count on backend b: the cells and the counts added onto `start`.
std::pair<std::vector<uint32_t>, std::vector<uint32_t>> assign_count_on(
    Backend& b, const Scene& s, const std::vector<uint32_t>& start) {
  auto pos = b.create<Real4>(s.points.size(), "positions");
  b.upload(pos, s.points);
  auto cells = b.create<uint32_t>(std::max<size_t>(s.points.size(), 1), "cells");
  auto counts = b.create<uint32_t>(start.size(), "counts");
  b.upload(counts, start);
  b.grid_assign_count({s.params}, pos, cells, counts);
  std::vector<uint32_t> c = b.download(cells);
  c.resize(s.points.size());
  return {c, b.download(counts)};
}

TEST_CASE("grid_assign_count equals grid_assign_cells + grid_count_cells and the CPU reference") {
  for (const GridCase& gc : kGridCases) {
    CAPTURE(gc.n);
    CAPTURE(gc.dims.x);
    const Scene s = make_scene(gc.n, gc.dims, gc.cell, 31 + gc.n);
    const uint32_t cell_count = uint32_t(grid_cell_count(s.params));
    std::vector<uint32_t> start(cell_count);
    for (uint32_t c = 0; c < cell_count; ++c) start[c] = c % 7;  // the kernel adds
    Backend& b = test::backend();
    const auto [cells, counts] = assign_count_on(b, s, start);
    // The two kernels it fuses, on the same backend.
    auto pos = b.create<Real4>(std::max<size_t>(gc.n, 1), "positions");
    if (gc.n) b.upload(pos, s.points);
    auto cells2 = b.create<uint32_t>(std::max<size_t>(gc.n, 1), "cells");
    auto idx = b.create<uint32_t>(std::max<size_t>(gc.n, 1), "indices");
    b.grid_assign_cells(s.params, pos, cells2, idx);
    std::vector<uint32_t> want_cells = b.download(cells2);
    want_cells.resize(gc.n);
    std::vector<uint32_t> want_counts = start;
    for (uint32_t c : want_cells) ++want_counts[c];
    CHECK(cells == want_cells);
    CHECK(counts == want_counts);
    const auto [ref_cells, ref_counts] = assign_count_on(test::reference(), s, start);
    CHECK(cells == ref_cells);
    CHECK(counts == ref_counts);
  }
}

TEST_CASE("grid_assign_count rejects a bad grid and buffers too small") {
  Backend& b = test::backend();
  auto pos = b.create<Real4>(4, "positions");
  auto cells = b.create<uint32_t>(4, "cells");
  auto counts = b.create<uint32_t>(63, "counts");
  b.upload(pos, std::vector<Vec4f>(4, Vec4f{0.5f, 0.5f, 0.5f, 0}));
  const GridParams g = make_grid_params({0, 0, 0}, 1.0f, {4, 4, 4}, 4);  // 64 cells
  CHECK_THROWS_WITH_AS(b.grid_assign_count({g}, pos, cells, counts),
                       doctest::Contains("grid_assign_count: invalid counts size = 63"), Error);
  auto counts64 = b.create<uint32_t>(64, "counts");
  b.fill(counts64, 0u);
  GridParams big = g;
  big.n = 5;
  CHECK_THROWS_WITH_AS(b.grid_assign_count({big}, pos, cells, counts64), doctest::Contains("n = 5"),
                       Error);
  GridParams flat = g;
  flat.dims = {0, 4, 4};
  CHECK_THROWS_WITH_AS(b.grid_assign_count({flat}, pos, cells, counts64), doctest::Contains("dims"),
                       Error);
  b.grid_assign_count({g}, pos, cells, counts64);
  CHECK(b.download(counts64)[(0 * 4 + 0) * 4 + 0] == 4);
}

LOOP_LIMIT_CASE("grid_assign_count does not loop", KernelId::grid_assign_count) {
  Backend& b = test::loop_counter();
  const uint32_t n = 1 << 16;
  auto pos = b.create<Real4>(n, "positions");
  auto cells = b.create<uint32_t>(n, "cells");
  auto counts = b.create<uint32_t>(8, "counts");
  b.fill(counts, 0u);
  b.upload(pos, std::vector<Vec4f>(n, Vec4f{0.1f, 0.1f, 0.1f, 0}));
  const GridParams g = make_grid_params({0, 0, 0}, 1.0f, {2, 2, 2}, n);
  b.grid_assign_count({g}, pos, cells, counts);  // every invocation on one cell
  CHECK(test::ticks_of(b) == 0);
  CHECK(b.download(counts)[0] == n);
}

LOOP_LIMIT_CASE("grid_count_cells does not loop", KernelId::grid_count_cells) {
  Backend& b = test::loop_counter();
  const uint32_t n = 1 << 16;
  auto cells = b.create<uint32_t>(n, "cells");
  auto counts = b.create<uint32_t>(1, "counts");
  b.fill(cells, 0u);
  b.fill(counts, 0u);
  b.grid_count_cells({n, 1}, cells, counts);  // every invocation on one cell
  CHECK(test::ticks_of(b) == 0);
  CHECK(b.download(counts)[0] == n);
}

namespace {

// The counting build with the device's largest cell cap.
GridBuildOptions counting(const Backend& b) {
  return {GridBuild::counting, max_walk_candidates(b)};
}

// Exclusive prefix sum of `counts`: each cell's run [start, end).
void host_runs(const std::vector<uint32_t>& counts, std::vector<uint32_t>& start,
               std::vector<uint32_t>& end) {
  start.resize(counts.size());
  end.resize(counts.size());
  uint32_t at = 0;
  for (size_t c = 0; c < counts.size(); ++c) {
    start[c] = at;
    at += counts[c];
    end[c] = at;
  }
}

// Equal non-empty cell ranges, and the same cells empty. An empty cell's range is [0, 0) after
// the radix build (the tables are cleared) and [k, k) after the counting build (k: the points in
// lower cells); both read as empty everywhere.
bool same_ranges(const GridResult& a, const GridResult& b) {
  if (a.start.size() != b.start.size() || a.end.size() != b.end.size()) return false;
  for (size_t c = 0; c < a.start.size(); ++c) {
    if (a.end[c] - a.start[c] != b.end[c] - b.start[c]) return false;
    if (a.end[c] != a.start[c] && a.start[c] != b.start[c]) return false;
  }
  return true;
}

}  // namespace

TEST_CASE("the counting build equals the radix build and the CPU reference, bit for bit") {
  uint64_t seed = 11;
  Backend& b = test::backend();
  for (const auto& c : kGridCases) {
    CAPTURE(c.n);
    CAPTURE(c.dims.x);
    const Scene s = make_scene(c.n, c.dims, c.cell, seed++);
    HashGrid g, g_radix;
    const GridResult got = build_on(b, s, &g, nullptr, counting(b));
    const GridResult radix = build_on(b, s, &g_radix);
    const GridResult ref =
        build_on(test::reference(), s, nullptr, nullptr, counting(test::reference()));
    CHECK(got.cells == radix.cells);
    CHECK(got.index == radix.index);
    CHECK(same_ranges(got, radix));
    CHECK(got.index == ref.index);
    CHECK(got.start == ref.start);
    // Its tables are prefix ranges, every cell's end the next one's start (the SPH kernels read
    // a row of 3 cells from its first start to its last end); the radix build's are not.
    CHECK(g.prefix_ranges);
    CHECK(!g_radix.prefix_ranges);
    REQUIRE(!got.start.empty());
    CHECK(got.start.front() == 0);
    CHECK(got.end.back() == c.n);
    size_t breaks = 0;
    for (size_t k = 0; k + 1 < got.start.size(); ++k) breaks += got.end[k] != got.start[k + 1];
    CHECK(breaks == 0);
    // The build leaves its count table zero: the next build needs no clear.
    const auto counts = b.download(g.counts);
    CHECK(std::count(counts.begin(), counts.end(), 0u) == ptrdiff_t(counts.size()));
  }
}

TEST_CASE("counting builds are deterministic: crowded cells, build after build") {
  Backend& b = test::backend();
  // ~800 points per cell, so the scatter's atomics contend and leave each cell in a new order.
  const Scene s = make_scene(50000, {4, 4, 4}, 0.25f, 21, 0.0f);
  auto pos = b.create<Real4>(s.points.size(), "positions");
  b.upload(pos, s.points);
  HashGrid g = make_hash_grid(b, s.params, s.points.size());
  build_hash_grid(b, g, pos, counting(b));
  const GridResult first = download(b, g);
  for (int again = 0; again < 3; ++again) {
    build_hash_grid(b, g, pos, counting(b));
    const GridResult next = download(b, g);
    CHECK(next.cells == first.cells);
    CHECK(next.index == first.index);
    CHECK(next.start == first.start);
    CHECK(next.end == first.end);
  }
  CHECK(first.index == build_on(b, s).index);  // and it is the radix build's order
}

TEST_CASE("grid_cell_offsets: cell runs from the counts, equal to a host scan") {
  std::mt19937 rng(43);
  Backend& b = test::backend();
  // One cell, a partial tile, past one and two scan levels (tiles of 2048 on every backend).
  for (const uint32_t cells : {1u, 7u, 2049u, (1u << 20) + 3, (1u << 22) + 5}) {
    CAPTURE(cells);
    std::vector<uint32_t> counts(cells), start, end;
    for (auto& c : counts) c = rng() % 4 == 0 ? rng() % 9 : 0;  // mostly empty cells
    host_runs(counts, start, end);
    auto cb = b.create<uint32_t>(cells, "counts");
    auto sb = b.create<uint32_t>(cells, "start");
    auto eb = b.create<uint32_t>(cells, "end");
    b.upload(cb, counts);
    b.fill(sb, 7u);
    b.fill(eb, 7u);
    b.grid_cell_offsets({cells}, cb, sb, eb);
    CHECK(b.download(sb) == start);
    CHECK(b.download(eb) == end);
    CHECK(b.download(cb) == counts);  // only read
  }
}

TEST_CASE("grid_scatter_cells fills each cell's run with its points and leaves counts zero") {
  std::mt19937 rng(44);
  Backend& b = test::backend();
  for (const uint32_t n : {1u, 1000u, 300007u}) {
    CAPTURE(n);
    const uint32_t cells = 4096;
    // A third of the points in one hot cell (contended atomics), the rest spread.
    std::vector<uint32_t> ids(n), counts(cells, 0), start, end;
    for (auto& id : ids) id = rng() % 3 == 0 ? 17 : rng() % cells;
    for (uint32_t id : ids) ++counts[id];
    host_runs(counts, start, end);
    auto cb = b.create<uint32_t>(n, "cells");
    auto eb = b.create<uint32_t>(cells, "end");
    auto kb = b.create<uint32_t>(cells, "counts");
    auto ub = b.create<uint32_t>(n, "unsorted");
    b.upload(cb, ids);
    b.upload(eb, end);
    b.upload(kb, counts);
    b.grid_scatter_cells({n, cells}, cb, eb, kb, ub);
    const auto got = b.download(ub);
    CHECK(b.download(kb) == std::vector<uint32_t>(cells, 0));
    size_t misplaced = 0;
    std::vector<uint32_t> seen(n, 0);
    for (uint32_t slot = 0; slot < n; ++slot) {
      REQUIRE(got[slot] < n);
      ++seen[got[slot]];
      const uint32_t c = ids[got[slot]];
      misplaced += slot < start[c] || slot >= end[c];
    }
    CHECK(misplaced == 0);
    CHECK(std::count(seen.begin(), seen.end(), 1u) == ptrdiff_t(n));  // a permutation
  }
}

TEST_CASE("grid_rank_in_cell orders each cell by index; a cell over max_per_cell is an error") {
  Backend& b = test::backend();
  // 100 points over 8 cells, cell 5 the fullest; each cell's run in reverse order.
  const uint32_t n = 100, cells = 8;
  std::vector<uint32_t> ids(n), counts(cells, 0), start, end;
  for (uint32_t i = 0; i < n; ++i) ids[i] = i % 10 == 3 ? 5 : i % 7;  // cell 7 stays empty
  for (uint32_t id : ids) ++counts[id];
  host_runs(counts, start, end);
  std::vector<uint32_t> runs(n), next = end;
  for (uint32_t i = 0; i < n; ++i) runs[--next[ids[i]]] = i;
  auto cb = b.create<uint32_t>(n, "cells");
  auto ub = b.create<uint32_t>(n, "unsorted");
  auto sb = b.create<uint32_t>(cells, "start");
  auto eb = b.create<uint32_t>(cells, "end");
  auto sorted_cells = b.create<uint32_t>(n, "sorted cells");
  auto sorted_index = b.create<uint32_t>(n, "sorted index");
  b.upload(cb, ids);
  b.upload(ub, runs);
  b.upload(sb, start);
  b.upload(eb, end);
  const uint32_t most = *std::max_element(counts.begin(), counts.end());
  b.grid_rank_in_cell({n, cells, most}, cb, ub, sb, eb, sorted_cells, sorted_index);
  std::vector<uint32_t> want_index(n);
  std::iota(want_index.begin(), want_index.end(), 0u);
  std::stable_sort(want_index.begin(), want_index.end(),
                   [&](uint32_t x, uint32_t y) { return ids[x] < ids[y]; });
  std::vector<uint32_t> want_cells(n);
  for (uint32_t k = 0; k < n; ++k) want_cells[k] = ids[want_index[k]];
  CHECK(b.download(sorted_index) == want_index);
  CHECK(b.download(sorted_cells) == want_cells);

  // One point fewer allowed than the fullest cell holds: the error names the cell and the cap.
  REQUIRE(std::max_element(counts.begin(), counts.end()) - counts.begin() == 5);
  CHECK_THROWS_WITH_AS(
      {
        b.grid_rank_in_cell({n, cells, most - 1}, cb, ub, sb, eb, sorted_cells, sorted_index);
        b.finish();
      },
      doctest::Contains(
          ("cell 5 holds more than max_per_cell = " + std::to_string(most - 1) + " points")
              .c_str()),
      Error);
  // A slot outside its point's cell run (a scatter of other cells) is caught, not written.
  std::swap(runs[0], runs[n - 1]);
  b.upload(ub, runs);
  CHECK_THROWS_WITH_AS(
      {
        b.grid_rank_in_cell({n, cells, most}, cb, ub, sb, eb, sorted_cells, sorted_index);
        b.finish();
      },
      doctest::Contains("slot 0 lies outside the cell run"), Error);
  // The cap is validated below the loop limit, naming the field.
  CHECK_THROWS_WITH_AS(
      b.grid_rank_in_cell({n, cells, 0}, cb, ub, sb, eb, sorted_cells, sorted_index),
      doctest::Contains("max_per_cell"), Error);
  CHECK_THROWS_WITH_AS(b.grid_rank_in_cell({n, cells, max_walk_candidates(b) + 1}, cb, ub, sb, eb,
                                           sorted_cells, sorted_index),
                       doctest::Contains("max_per_cell"), Error);
  CHECK_THROWS_WITH_AS(
      b.grid_rank_in_cell({n + 1, cells, most}, cb, ub, sb, eb, sorted_cells, sorted_index),
      doctest::Contains("n = 101"), Error);
  CHECK_THROWS_WITH_AS(
      b.grid_rank_in_cell({n, cells + 1, most}, cb, ub, sb, eb, sorted_cells, sorted_index),
      doctest::Contains("cell_count"), Error);
}

TEST_CASE("a counting build over max_per_cell fails clearly and leaves the grid reusable") {
  Backend& b = test::backend();
  const Scene s = make_scene(3000, {1, 1, 1}, 1.0f, 3, 0.0f);  // all in one cell
  auto pos = b.create<Real4>(s.points.size(), "positions");
  b.upload(pos, s.points);
  HashGrid g = make_hash_grid(b, s.params, s.points.size());
  CHECK_THROWS_WITH_AS(
      {
        build_hash_grid(b, g, pos, {GridBuild::counting, 2999});
        b.finish();
      },
      doctest::Contains("cell 0 holds more than max_per_cell = 2999 points"), Error);
  // The scatter counted the table back down, so the next build needs no clear.
  build_hash_grid(b, g, pos, {GridBuild::counting, 3000});
  const GridResult r = download(b, g);
  CHECK(r.end[0] == 3000);
  CHECK(r.index == build_on(b, s).index);
}

TEST_CASE("grid_scatter_cells reports a point with no slot and leaves the table as it was") {
  Backend& b = test::backend();
  auto cells = b.create<uint32_t>(4, "cells");
  auto end = b.create<uint32_t>(8, "end");
  auto counts = b.create<uint32_t>(8, "counts");
  auto unsorted = b.create<uint32_t>(4, "unsorted");
  b.upload(cells, std::vector<uint32_t>{0, 3, 3, 3});
  b.upload(end, std::vector<uint32_t>{1, 1, 1, 3, 3, 3, 3, 3});
  b.upload(counts, std::vector<uint32_t>{1, 0, 0, 2, 0, 0, 0, 0});  // cell 3 counted short
  CHECK_THROWS_WITH_AS(
      {
        b.grid_scatter_cells({4, 8}, cells, end, counts, unsorted);
        b.finish();
      },
      doctest::Contains("has no free slot"), Error);
  CHECK(b.download(counts) == std::vector<uint32_t>(8, 0));
  CHECK_THROWS_WITH_AS(b.grid_scatter_cells({5, 8}, cells, end, counts, unsorted),
                       doctest::Contains("n = 5"), Error);
  CHECK_THROWS_WITH_AS(b.grid_scatter_cells({4, 9}, cells, end, counts, unsorted),
                       doctest::Contains("cell_count"), Error);
  CHECK_THROWS_WITH_AS(b.grid_cell_offsets({9}, counts, end, end), doctest::Contains("cell_count"),
                       Error);
  CHECK_THROWS_WITH_AS(b.grid_cell_offsets({0}, counts, end, end), doctest::Contains("cell_count"),
                       Error);
}

LOOP_LIMIT_CASE("counting-sort passes: offsets and scatter bounded, rank = its cell's points",
                KernelId::grid_cell_offsets, KernelId::grid_scatter_cells,
                KernelId::grid_rank_in_cell) {
  Backend& b = test::loop_counter();
  // The offsets' loops do not grow with the cell count (the chunk sums take two scan levels).
  const uint32_t cells = (1u << 22) + 5;
  auto counts = b.create<uint32_t>(cells, "counts");
  auto start = b.create<uint32_t>(cells, "start");
  auto end = b.create<uint32_t>(cells, "end");
  b.fill(counts, 1u);
  (void)test::ticks_of(b);
  b.grid_cell_offsets({cells}, counts, start, end);
  const uint32_t scan_ticks = test::ticks_of(b);
  MESSAGE("grid_cell_offsets worst invocation: " << scan_ticks << " loop iterations");
  CHECK(scan_ticks >= kCellOffsetChunk);  // each chunk pass loops over its chunk
  // The scan of the chunk sums: four loops over a thread's 8 items and two over the subgroups of
  // a 256-wide workgroup (at most 64, at subgroup size 4); independent of the cell count.
  CHECK(scan_ticks <= 4 * 8 + 2 * 64);

  // The rank's worst case: every point in one cell.
  const uint32_t n = 4000;
  const GridParams gp = make_grid_params({0, 0, 0}, 1.0f, {1, 1, 1}, n);
  std::vector<Vec4f> pts(n, Vec4f{0.5f, 0.5f, 0.5f, 0.0f});
  auto pos = b.create<Real4>(n, "pos");
  b.upload(pos, pts);
  HashGrid g = make_hash_grid(b, gp, n);
  build_hash_grid(b, g, pos, {GridBuild::counting, n});
  CHECK(test::ticks_of(b) == n);  // the rank's loop over the cell: the counter measures it
  b.grid_count_cells({n, 1}, g.point_cells, g.counts);
  (void)test::ticks_of(b);
  b.grid_scatter_cells({n, 1}, g.point_cells, g.cell_end, g.counts, g.unsorted);
  CHECK(test::ticks_of(b) == 0);  // every point on one cell's counter, no loop
  // The validated maximum of max_per_cell keeps the worst invocation under the limit.
  const uint32_t most = max_walk_candidates(b);
  CHECK(most + 1 < b.caps().max_loop_iterations);
  CHECK_THROWS_AS(b.grid_rank_in_cell({n, 1, most + 1}, g.point_cells, g.unsorted, g.cell_start,
                                      g.cell_end, g.sorted_cells, g.sorted_index),
                  Error);
}
