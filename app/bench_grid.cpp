// `masav bench grid`: hash-grid build (cells, sort, ranges), reorder and the 27-cell neighbour
// query per backend, stage by stage with device timestamps, for the radix build, the counting
// build or both (engine/grid/hash_grid.h).
#include <fmt/format.h>

#include <cmath>
#include <random>

#include "app/bench_common.h"
#include "app/vocabulary.h"
#include "engine/core/error.h"
#include "engine/grid/hash_grid.h"
#include "engine/kernels/kernel_checks.h"

namespace masav::app {

struct GridBenchOptions : BenchOptions {
  uint32_t n = 1u << 20;
  double per_cell = 8.0;
  std::string build = "radix";  // radix, counting or both
  int reps = 5;
};

namespace {

const char* kStages[] = {"assign", "sort", "ranges", "reorder", "neighbours"};
enum Stage { kAssign, kSort, kRanges, kReorder, kNeighbours, kStageCount };

// Each stage's device timestamps, begin and end.
struct StageStamps {
  TimestampId begin[kStageCount], end[kStageCount];
};

// The build's passes, stamped by stage. The counting build knows its ranges before it sorts:
// its "assign" is the assignment with the counts (grid_assign_count), its "ranges" the offsets,
// its "sort" the scatter and the rank.
void build_stages(Backend& b, HashGrid& g, const Buffer<Real4>& pos, GridBuild build,
                  StageStamps& t) {
  const GridParams& gp = g.params;
  t.begin[kAssign] = b.timestamp();
  if (build == GridBuild::radix) {
    b.grid_assign_cells(gp, pos, g.sorted_cells, g.sorted_index);
    t.end[kAssign] = t.begin[kSort] = b.timestamp();
    b.radix_sort({gp.n, grid_key_bits(gp)}, g.sorted_cells, &g.sorted_index);
    t.end[kSort] = t.begin[kRanges] = b.timestamp();
    b.grid_cell_ranges(gp, g.sorted_cells, g.cell_start, g.cell_end);
    t.end[kRanges] = b.timestamp();
    return;
  }
  const uint32_t cells = uint32_t(grid_cell_count(gp));
  b.grid_assign_count({gp}, pos, g.point_cells, g.counts);
  t.end[kAssign] = t.begin[kRanges] = b.timestamp();
  b.grid_cell_offsets({cells}, g.counts, g.cell_start, g.cell_end);
  t.end[kRanges] = t.begin[kSort] = b.timestamp();
  b.grid_scatter_cells({gp.n, cells}, g.point_cells, g.cell_end, g.counts, g.unsorted);
  b.grid_rank_in_cell({gp.n, cells, max_walk_candidates(b)}, g.point_cells, g.unsorted,
                      g.cell_start, g.cell_end, g.sorted_cells, g.sorted_index);
  t.end[kSort] = b.timestamp();
}

std::vector<GridBuild> builds_of(const std::string& choice) {
  if (choice == "both") return {GridBuild::radix, GridBuild::counting};
  return {choice == "counting" ? GridBuild::counting : GridBuild::radix};
}

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
  fmt::print("  {:<8} {:<9} {:<34} {:>9} {:>9} {:>9} {:>9} {:>10} {:>12}\n", "backend", "build",
             "device", "assign", "sort", "ranges", "reorder", "neighbours", "Mpts/s build");
  const int rc = for_each_backend(open_backends(o.choice), [&](Backend& b) {
    auto pos = b.create<Real4>(o.n, "positions");
    auto sorted = b.create<Real4>(o.n, "sorted positions");
    auto counts = b.create<uint32_t>(o.n, "counts");
    b.upload(pos, pts);
    HashGrid g = make_hash_grid(b, gp, o.n);
    if (o.build != "radix")  // the counting build's buffers, made outside the timed runs
      build_hash_grid(b, g, pos, {GridBuild::counting, max_walk_candidates(b)});
    const NeighborParams np = make_neighbor_params(gp, gp.cell_size);
    for (const GridBuild build : builds_of(o.build)) {
      const char* build_name = build == GridBuild::radix ? "radix" : "counting";
      std::vector<double> stage_ms[kStageCount];
      for (int rep = 0; rep < o.reps + 1; ++rep) {
        b.finish();
        b.reset_timestamps();
        StageStamps t;
        build_stages(b, g, pos, build, t);
        t.begin[kReorder] = b.timestamp();
        reorder(b, g, pos.impl(), sorted.impl());
        t.end[kReorder] = t.begin[kNeighbours] = b.timestamp();
        b.grid_count_neighbors(np, sorted, g.cell_start, g.cell_end, counts);
        t.end[kNeighbours] = b.timestamp();
        b.finish();
        if (rep == 0) continue;  // warm-up
        for (int s = 0; s < kStageCount; ++s)
          stage_ms[s].push_back((b.timestamp_ns(t.end[s]) - b.timestamp_ns(t.begin[s])) * 1e-6);
      }
      TimingStats st[kStageCount];
      for (int s = 0; s < kStageCount; ++s) st[s] = summarize(stage_ms[s]);
      const double build_ms = st[kAssign].median_ms + st[kSort].median_ms + st[kRanges].median_ms;
      fmt::print(
          "  {:<8} {:<9} {:<34.34} {:>9.3f} {:>9.3f} {:>9.3f} {:>9.3f} {:>10.3f} {:>12.1f}\n",
          b.name(), build_name, b.caps().device_name, st[kAssign].median_ms, st[kSort].median_ms,
          st[kRanges].median_ms, st[kReorder].median_ms, st[kNeighbours].median_ms,
          o.n / build_ms * 1e-3);
      begin_row(j, b);
      j.field("build", build_name).field("reps", o.reps).key("median_ms").begin_object();
      for (int s = 0; s < kStageCount; ++s) j.field(kStages[s], st[s].median_ms);
      j.end_object().field("build_points_per_s", o.n / (build_ms * 1e-3)).end_object();
    }
  });
  j.end_array();
  return rc;
}

}  // namespace

void add_grid_bench(CLI::App& bench) {
  static GridBenchOptions o;
  auto* cmd =
      add_bench(bench, "grid", "hash-grid build, reorder and neighbour query", o, run_grid_bench);
  add_ranged_option(*cmd, "--particles", o.n, "points (particles) in the grid", 1u, 1u << 26);
  add_old_option(*cmd, "--n", "--particles", o.n)->check(CLI::Range(1u, 1u << 26));
  add_ranged_option(*cmd, "--per-cell", o.per_cell, "mean points per cell", 0.5, 1000.0);
  cmd->add_option("--build", o.build,
                  "grid build timed: radix (sort, then ranges), counting (ranges = count + "
                  "offsets, sort = scatter + rank) or both")
      ->check(CLI::IsMember({"radix", "counting", "both"}))
      ->capture_default_str();
  add_reps_option(*cmd, o.reps);
  add_json_option(*cmd, o.json);
}

}  // namespace masav::app
