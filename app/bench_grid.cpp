// `masav bench grid`: hash-grid build (cells, sort, ranges), reorder and the 27-cell neighbour
// query per backend, stage by stage with device timestamps.
#include <fmt/format.h>

#include <cmath>
#include <random>

#include "app/bench_common.h"
#include "engine/core/error.h"
#include "engine/grid/hash_grid.h"

namespace masav::app {

struct GridBenchOptions : BenchOptions {
  uint32_t n = 1u << 20;
  double per_cell = 8.0;
  int reps = 5;
};

namespace {

const char* kStages[] = {"assign", "sort", "ranges", "reorder", "neighbours"};
constexpr int kStageCount = 5;

int run_grid_bench(const GridBenchOptions& o, JsonWriter& j) {
  const uint32_t side = std::max(1u, uint32_t(std::lround(std::cbrt(o.n / o.per_cell))));
  const GridParams gp = make_grid_params({0, 0, 0}, 1.0f / float(side), {side, side, side}, o.n);
  fmt::print("bench grid: {} points uniform in {}^3 cells (~{:.1f} per cell), median of {} runs\n",
             o.n, side, double(o.n) / (double(side) * side * side), o.reps);
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<Vec4f> pts(o.n);
  for (auto& p : pts) p = {u(rng), u(rng), u(rng), 0.0f};

  j.field("n", o.n).field("cells_per_axis", side).key("rows").begin_array();
  fmt::print("  {:<8} {:<34} {:>9} {:>9} {:>9} {:>9} {:>10} {:>12}\n", "backend", "device",
             "assign", "sort", "ranges", "reorder", "neighbours", "Mpts/s build");
  const int rc = for_each_backend(open_backends(o.choice), [&](Backend& b) {
    auto pos = b.create<Real4>(o.n, "positions");
    auto sorted = b.create<Real4>(o.n, "sorted positions");
    auto counts = b.create<uint32_t>(o.n, "counts");
    b.upload(pos, pts);
    HashGrid g = make_hash_grid(b, gp, o.n);
    const NeighborParams np = make_neighbor_params(gp, gp.cell_size);
    std::vector<double> stage_ms[kStageCount];
    for (int rep = 0; rep < o.reps + 1; ++rep) {
      b.finish();
      b.reset_timestamps();
      TimestampId t[kStageCount + 1];
      t[0] = b.timestamp();
      b.grid_assign_cells(gp, pos, g.sorted_cells, g.sorted_index);
      t[1] = b.timestamp();
      b.radix_sort({o.n, grid_key_bits(gp)}, g.sorted_cells, &g.sorted_index);
      t[2] = b.timestamp();
      b.grid_cell_ranges(gp, g.sorted_cells, g.cell_start, g.cell_end);
      t[3] = b.timestamp();
      reorder(b, g, pos.impl(), sorted.impl());
      t[4] = b.timestamp();
      b.grid_count_neighbors(np, sorted, g.cell_start, g.cell_end, counts);
      t[5] = b.timestamp();
      b.finish();
      if (rep == 0) continue;  // warm-up
      for (int s = 0; s < kStageCount; ++s)
        stage_ms[s].push_back((b.timestamp_ns(t[s + 1]) - b.timestamp_ns(t[s])) * 1e-6);
    }
    TimingStats st[kStageCount];
    for (int s = 0; s < kStageCount; ++s) st[s] = summarize(stage_ms[s]);
    const double build_ms = st[0].median_ms + st[1].median_ms + st[2].median_ms;
    fmt::print("  {:<8} {:<34.34} {:>9.3f} {:>9.3f} {:>9.3f} {:>9.3f} {:>10.3f} {:>12.1f}\n",
               b.name(), b.caps().device_name, st[0].median_ms, st[1].median_ms, st[2].median_ms,
               st[3].median_ms, st[4].median_ms, o.n / build_ms * 1e-3);
    begin_row(j, b);
    j.field("reps", o.reps).key("median_ms").begin_object();
    for (int s = 0; s < kStageCount; ++s) j.field(kStages[s], st[s].median_ms);
    j.end_object().field("build_points_per_s", o.n / (build_ms * 1e-3)).end_object();
  });
  j.end_array();
  return rc;
}

}  // namespace

void add_grid_bench(CLI::App& bench) {
  static GridBenchOptions o;
  auto* cmd =
      add_bench(bench, "grid", "hash-grid build, reorder and neighbour query", o, run_grid_bench);
  add_ranged_option(*cmd, "--n", o.n, "points", 1u, 1u << 26);
  add_ranged_option(*cmd, "--per-cell", o.per_cell, "mean points per cell", 0.5, 1000.0);
  add_reps_option(*cmd, o.reps);
  add_json_option(*cmd, o.json);
}

}  // namespace masav::app
