// Hash grid: cells, sorted (cell, index), cell ranges and reorder equal the CPU reference bit for
// bit and a brute-force grouping; the 27-cell neighbour count equals an O(n^2) search; the cell
// counts of a counting sort equal a host count and the grid's cell ranges.
#include <doctest/doctest.h>

#include <cstring>
#include <map>
#include <random>
#include <vector>

#include "engine/core/error.h"
#include "engine/grid/hash_grid.h"
#include "engine/kernels/grid_cell.h"
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

struct GridResult {
  std::vector<uint32_t> cells, index, start, end;
};

GridResult build_on(Backend& b, const Scene& s, HashGrid* keep = nullptr,
                    Buffer<Real4>* pos_out = nullptr) {
  auto pos = b.create<Real4>(s.points.size(), "positions");
  b.upload(pos, s.points);
  HashGrid g = make_hash_grid(b, s.params, s.points.size());
  build_hash_grid(b, g, pos);
  GridResult r{b.download(g.sorted_cells), b.download(g.sorted_index), b.download(g.cell_start),
               b.download(g.cell_end)};
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
  struct Case {
    uint32_t n;
    UVec3 dims;
    float cell;
  };
  const Case cases[] = {{0, {4, 4, 4}, 0.5f},           {1, {4, 4, 4}, 0.5f},
                        {2, {1, 1, 1}, 3.0f},           {1000, {13, 7, 29}, 0.1f},
                        {100003, {64, 32, 48}, 0.03f},  {5000, {1, 1, 1}, 1.0f},
                        {20000, {512, 256, 64}, 0.001f}};
  uint64_t seed = 11;
  for (const auto& c : cases) {
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
