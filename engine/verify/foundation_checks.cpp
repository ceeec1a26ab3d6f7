// Cross-checks of the foundation's kernels: Philox, the radix sort and the hash-grid kernels
// (the passes of the counting sort by cell included), all integer results, so bit for bit.
// Inputs come from the scene (its point count, seed and grid), generated on the host and
// uploaded identically to both backends.
#include "engine/verify/foundation_checks.h"

#include <algorithm>
#include <cstring>
#include <numeric>
#include <random>

#include "engine/grid/hash_grid.h"

namespace masav::verify {
namespace {

GridParams grid_or_default(const CheckInputs& in) {
  if (in.grid) {
    GridParams g = *in.grid;
    g.n = in.points;
    return g;
  }
  return make_grid_params({0, 0, 0}, 1.0f / 16, {16, 16, 16}, in.points);
}

// The grid built from the shared check points, with the positions left in `pos`.
HashGrid grid_on(Backend& b, const CheckInputs& in, Buffer<Real4>& pos) {
  const GridParams g = grid_or_default(in);
  pos = b.create<Real4>(in.points, "check positions");
  b.upload(pos, check_points(in));
  HashGrid grid = make_hash_grid(b, g, in.points);
  build_hash_grid(b, grid, pos);
  return grid;
}

// Cell ids drawn on the host for the counting-sort passes, with each cell's count and run: every
// third point in one hot cell (at most 1024 of them, so the rank pass's loops stay short), so
// the atomics contend, the rest spread over the scene's cells.
struct CellTable {
  uint32_t cell_count = 0;
  std::vector<uint32_t> ids, counts, start, end;
};

CellTable cell_table(const CheckInputs& in) {
  CellTable t;
  t.cell_count = uint32_t(grid_cell_count(grid_or_default(in)));
  std::mt19937 rng(uint32_t(in.seed) + 1);
  t.ids.resize(in.points);
  for (uint32_t i = 0; i < in.points; ++i)
    t.ids[i] = i % 3 == 0 && i < 3 * 1024 ? t.cell_count / 2 : rng() % t.cell_count;
  t.counts.assign(t.cell_count, 0);
  for (uint32_t id : t.ids) ++t.counts[id];
  t.start.resize(t.cell_count);
  t.end.resize(t.cell_count);
  uint32_t at = 0;
  for (uint32_t c = 0; c < t.cell_count; ++c) {
    t.start[c] = at;
    at += t.counts[c];
    t.end[c] = at;
  }
  return t;
}

Buffer<uint32_t> uploaded(Backend& b, const std::vector<uint32_t>& words, const char* label) {
  auto buf = b.create<uint32_t>(words.size(), label);
  b.upload(buf, words);
  return buf;
}

// The rank passes' inputs: a host scatter of cell_table(in), each cell's run reversed (the order
// the pass must undo), uploaded, with outputs to fill.
struct RankInputs {
  CellTable table;
  CellRankParams params;
  Buffer<uint32_t> cells, unsorted, start, end, sorted_cells, sorted_index;
  RankInputs(Backend& b, const CheckInputs& in) : table(cell_table(in)) {
    std::vector<uint32_t> runs(in.points), next = table.end;
    for (uint32_t i = 0; i < in.points; ++i) runs[--next[table.ids[i]]] = i;
    const uint32_t most = *std::max_element(table.counts.begin(), table.counts.end());
    params = {in.points, table.cell_count, std::max(most, 1u)};
    cells = uploaded(b, table.ids, "check cells");
    unsorted = uploaded(b, runs, "check unsorted");
    start = uploaded(b, table.start, "check cell start");
    end = uploaded(b, table.end, "check cell end");
    sorted_cells = b.create<uint32_t>(in.points, "check sorted cells");
    sorted_index = b.create<uint32_t>(in.points, "check sorted index");
  }
};

}  // namespace

std::vector<KernelCheck> foundation_checks() {
  std::vector<KernelCheck> c;
  c.push_back(exact_check(KernelId::philox_u32, [](Backend& b, const CheckInputs& in) {
    auto out = b.create<uint32_t>(4 * size_t(in.points), "check philox");
    b.philox_u32({in.seed, 7, 0}, out);
    return CheckOutputs{{"words", b.download(out), {}}};
  }));
  c.push_back(exact_check(KernelId::philox_uniform, [](Backend& b, const CheckInputs& in) {
    auto out = b.create<float>(4 * size_t(in.points), "check uniforms");
    b.philox_uniform({in.seed, 0, 0}, out);
    const auto f = b.download(out);
    std::vector<uint32_t> bits(f.size());
    std::memcpy(bits.data(), f.data(), 4 * f.size());
    return CheckOutputs{{"float bits", bits, {}}};
  }));
  c.push_back(exact_check(KernelId::radix_sort, [](Backend& b, const CheckInputs& in) {
    std::mt19937 rng(uint32_t(in.seed));
    std::vector<uint32_t> keys(in.points), values(in.points);
    for (auto& k : keys) k = rng();
    std::iota(values.begin(), values.end(), 0u);
    auto kb = b.create<uint32_t>(in.points, "check keys");
    auto vb = b.create<uint32_t>(in.points, "check values");
    b.upload(kb, keys);
    b.upload(vb, values);
    b.radix_sort({in.points, 32}, kb, &vb);
    return CheckOutputs{{"keys", b.download(kb), {}}, {"values", b.download(vb), {}}};
  }));
  c.push_back(exact_check(KernelId::grid_assign_cells, [](Backend& b, const CheckInputs& in) {
    const GridParams g = grid_or_default(in);
    auto pos = b.create<Real4>(in.points, "check positions");
    b.upload(pos, check_points(in));
    auto cells = b.create<uint32_t>(in.points, "check cells");
    auto idx = b.create<uint32_t>(in.points, "check indices");
    b.grid_assign_cells(g, pos, cells, idx);
    return CheckOutputs{{"cells", b.download(cells), {}}, {"indices", b.download(idx), {}}};
  }));
  c.push_back(exact_check(KernelId::grid_cell_ranges, [](Backend& b, const CheckInputs& in) {
    Buffer<Real4> pos;
    HashGrid g = grid_on(b, in, pos);
    return CheckOutputs{{"sorted cells", b.download(g.sorted_cells), {}},
                        {"cell start", b.download(g.cell_start), {}},
                        {"cell end", b.download(g.cell_end), {}}};
  }));
  c.push_back(exact_check(KernelId::gather, [](Backend& b, const CheckInputs& in) {
    Buffer<Real4> pos;
    HashGrid g = grid_on(b, in, pos);
    auto sorted = b.create<Real4>(in.points, "check sorted");
    reorder(b, g, pos.impl(), sorted.impl());
    const auto f = b.download_f32(sorted);
    std::vector<uint32_t> bits(4 * f.size());
    std::memcpy(bits.data(), f.data(), 16 * f.size());
    return CheckOutputs{{"sorted positions (fp32 bits)", bits, {}}};
  }));
  c.push_back(exact_check(KernelId::grid_count_neighbors, [](Backend& b, const CheckInputs& in) {
    Buffer<Real4> pos;
    HashGrid g = grid_on(b, in, pos);
    auto sorted = b.create<Real4>(in.points, "check sorted");
    reorder(b, g, pos.impl(), sorted.impl());
    auto counts = b.create<uint32_t>(in.points, "check counts");
    const float r = in.neighbor_radius > 0 ? in.neighbor_radius : g.params.cell_size;
    b.grid_count_neighbors(make_neighbor_params(g.params, r), sorted, g.cell_start, g.cell_end,
                           counts);
    return CheckOutputs{{"counts", b.download(counts), {}}};
  }));
  // grid_count_cells: ids drawn on the host, a third in one cell so the atomics contend, counted
  // onto a table that already holds counts (the kernel adds).
  c.push_back(exact_check(KernelId::grid_count_cells, [](Backend& b, const CheckInputs& in) {
    const uint32_t cell_count = uint32_t(grid_cell_count(grid_or_default(in)));
    std::mt19937 rng(uint32_t(in.seed));
    std::vector<uint32_t> ids(in.points), start(cell_count);
    for (auto& id : ids) id = rng() % 3 == 0 ? cell_count / 2 : rng() % cell_count;
    std::iota(start.begin(), start.end(), 0u);
    auto cells = b.create<uint32_t>(ids.size(), "check cells");
    auto counts = b.create<uint32_t>(cell_count, "check counts");
    b.upload(cells, ids);
    b.upload(counts, start);
    b.grid_count_cells({in.points, cell_count}, cells, counts);
    return CheckOutputs{{"counts", b.download(counts), {}}};
  }));
  // grid_assign_count: the check points' cells, counted onto a table that already holds counts.
  c.push_back(exact_check(KernelId::grid_assign_count, [](Backend& b, const CheckInputs& in) {
    const GridParams g = grid_or_default(in);
    const uint32_t cell_count = uint32_t(grid_cell_count(g));
    auto pos = b.create<Real4>(in.points, "check positions");
    b.upload(pos, check_points(in));
    std::vector<uint32_t> start(cell_count);
    std::iota(start.begin(), start.end(), 0u);
    auto cells = b.create<uint32_t>(in.points, "check cells");
    auto counts = b.create<uint32_t>(cell_count, "check counts");
    b.upload(counts, start);
    b.grid_assign_count({g}, pos, cells, counts);
    return CheckOutputs{{"cells", b.download(cells), {}}, {"counts", b.download(counts), {}}};
  }));
  c.push_back(exact_check(KernelId::grid_cell_offsets, [](Backend& b, const CheckInputs& in) {
    const CellTable t = cell_table(in);
    auto counts = uploaded(b, t.counts, "check counts");
    auto start = b.create<uint32_t>(t.cell_count, "check cell start");
    auto end = b.create<uint32_t>(t.cell_count, "check cell end");
    b.grid_cell_offsets({t.cell_count}, counts, start, end);
    return CheckOutputs{{"cell start", b.download(start), {}}, {"cell end", b.download(end), {}}};
  }));
  // The scatter's order within a cell depends on timing, so each cell's run is compared sorted;
  // the count table must come back all zero.
  c.push_back(exact_check(KernelId::grid_scatter_cells, [](Backend& b, const CheckInputs& in) {
    const CellTable t = cell_table(in);
    auto cells = uploaded(b, t.ids, "check cells");
    auto end = uploaded(b, t.end, "check cell end");
    auto counts = uploaded(b, t.counts, "check counts");
    auto unsorted = b.create<uint32_t>(in.points, "check unsorted");
    b.grid_scatter_cells({in.points, t.cell_count}, cells, end, counts, unsorted);
    std::vector<uint32_t> runs = b.download(unsorted);
    for (uint32_t c = 0; c < t.cell_count; ++c)
      std::sort(runs.begin() + t.start[c], runs.begin() + t.end[c]);
    return CheckOutputs{{"each cell's points", runs, {}}, {"counts after", b.download(counts), {}}};
  }));
  // The rank pass from a scatter made on the host, each cell's run reversed (the order the
  // pass must undo).
  c.push_back(exact_check(KernelId::grid_rank_in_cell, [](Backend& b, const CheckInputs& in) {
    RankInputs r(b, in);
    b.grid_rank_in_cell(r.params, r.cells, r.unsorted, r.start, r.end, r.sorted_cells,
                        r.sorted_index);
    return CheckOutputs{{"sorted cells", b.download(r.sorted_cells), {}},
                        {"sorted index", b.download(r.sorted_index), {}}};
  }));
  // The same rank pass moving two 4-vectors and an id per point; the vectors hold integers
  // below 2^24, which every backend's precision stores exactly, so the moved data compare bit
  // for bit.
  c.push_back(exact_check(KernelId::grid_rank_and_move, [](Backend& b, const CheckInputs& in) {
    RankInputs r(b, in);
    std::vector<uint32_t> ids(in.points);
    std::vector<Vec4d> va(in.points), vb(in.points);
    for (uint32_t i = 0; i < in.points; ++i) {
      va[i] = {double(i), double(2 * i + 1), double(r.table.ids[i] % 4096), 0.5};
      vb[i] = {-double(i), double(i % 977), 3.0, double(in.points - i)};
      ids[i] = i * 2654435761u;
    }
    auto a = b.create<Real4>(in.points, "check a");
    auto a_sorted = b.create<Real4>(in.points, "check a sorted");
    auto bb = b.create<Real4>(in.points, "check b");
    auto b_sorted = b.create<Real4>(in.points, "check b sorted");
    auto id_in = uploaded(b, ids, "check ids");
    auto id_sorted = b.create<uint32_t>(in.points, "check ids sorted");
    b.upload(a, va);
    b.upload(bb, vb);
    b.grid_rank_and_move(r.params, r.cells, r.unsorted, r.start, r.end, r.sorted_cells,
                         r.sorted_index, a, a_sorted, bb, b_sorted, id_in, id_sorted);
    auto words = [&](const Buffer<Real4>& v) {
      std::vector<uint32_t> w;
      for (const Vec4d& x : b.download(v))
        for (double e : {x.x, x.y, x.z, x.w}) w.push_back(uint32_t(int64_t(e * 2.0)));
      return w;
    };
    return CheckOutputs{{"sorted cells", b.download(r.sorted_cells), {}},
                        {"sorted index", b.download(r.sorted_index), {}},
                        {"a moved", words(a_sorted), {}},
                        {"b moved", words(b_sorted), {}},
                        {"ids moved", b.download(id_sorted), {}}};
  }));
  return c;
}

}  // namespace masav::verify
