// `masav bench light`: nebula lighting (illumination + view, thesis Eq. 2.4-2.6) for the thesis's
// Table 2.3 states and particle counts on each backend, beside the thesis's CPU and GPU times;
// and run time against error of the midpoint optical-depth path against the exact traversal.
#include <fmt/format.h>

#include <cmath>

#include "app/bench_atom_common.h"
#include "app/progress.h"
#include "engine/atom/atom_scene.h"
#include "engine/core/error.h"

namespace masav::app {

struct LightBenchOptions : Table23Options {
  uint32_t photons = 256;  // the table only feeds the lookups here
};

namespace {

int run_light_bench(const LightBenchOptions& o, JsonWriter& j) {
  fmt::print(
      "bench light: nebula lighting for thesis Table 2.3 (counts x {}), 60^3 density "
      "grid, exact path, median of {} runs\n",
      o.scale, o.reps);
  j.field("scale", o.scale).field("density_dims", 60).key("rows").begin_array();
  auto backends = open_backends(o.choice, "--scale 0.1 --reps 1");
  fmt::print("  {:<8} {:<8} {:>9} {:>10} {:>10} {:>10} {:>11} {:>11}\n", "backend", "state",
             "particles", "illum ms", "view ms", "total ms", "thesis GPU", "thesis CPU");
  int rc = for_each_thesis_row(
      backends, o.scale, [&](Backend& b, const ThesisRow& row, uint32_t particles) {
        atom::AtomScene scene(b, bench_scene_options(row.state, particles, o.photons));
        scene.build_cloud();
        scene.build_density();
        scene.build_table();
        scene.illuminate();
        scene.view();
        const NebulaLightParams lp = scene.light_params();
        const TimingStats si = time_work(b, o.reps, [&] {
          b.nebula_illuminate(lp, scene.positions, scene.density, scene.illumination);
        });
        const TimingStats sv = time_work(b, o.reps, [&] {
          b.nebula_view(lp, scene.positions, scene.density, scene.phase, scene.illumination,
                        scene.light);
        });
        const double total = si.median_ms + sv.median_ms;
        fmt::print("  {:<8} {:<8} {:>9} {:>10.2f} {:>10.2f} {:>10.2f} {:>10.3f}s {:>10.1f}s\n",
                   b.name(), row.state, particles, si.median_ms, sv.median_ms, total,
                   row.color_gpu_s, row.color_cpu_s);
        begin_row(j, b);
        j.field("state", row.state).field("particles", particles);
        j.field("illuminate_ms", si.median_ms).field("view_ms", sv.median_ms);
        j.field("total_ms", total).field("thesis_gpu_s", row.color_gpu_s);
        j.field("thesis_cpu_s", row.color_cpu_s).end_object();
      });
  j.end_array();
  // Midpoint steps against the exact traversal (state 3, 100k particles).
  fmt::print(
      "  optical-depth path: midpoint step vs error against the exact traversal (state3):\n");
  fmt::print("  {:<8} {:>12} {:>10} {:>14}\n", "backend", "step (cells)", "ms", "rel L2 light");
  j.key("sweep").begin_array();
  Progress progress("optical-depth paths", backends.size() * 6);
  rc |= for_each_backend(backends, [&](Backend& b) {
    atom::AtomScene scene(b, bench_scene_options("state3", 100000, o.photons));
    scene.run_all();
    NebulaLightParams lp = scene.light_params();
    auto run = [&] {
      b.nebula_illuminate(lp, scene.positions, scene.density, scene.illumination);
      b.nebula_view(lp, scene.positions, scene.density, scene.phase, scene.illumination,
                    scene.light);
    };
    run();
    const std::vector<double> exact = b.download(scene.light);
    const TimingStats se = time_work(b, o.reps, run);
    j.begin_object().field("backend", b.name()).field("path", "exact");
    j.field("ms", se.median_ms).field("rel_l2", 0.0).end_object();
    fmt::print("  {:<8} {:>12} {:>10.2f} {:>14}\n", b.name(), "exact", se.median_ms, "0");
    progress.advance(b.name() + " exact");
    lp.path = OpticalPath::midpoint;
    for (double cells : {2.0, 1.0, 0.5, 0.25, 0.125}) {
      lp.step_a0 = float(cells * lp.grid.cell_size);
      const TimingStats s = time_work(b, o.reps, run);
      const std::vector<double> got = b.download(scene.light);
      double d2 = 0, r2 = 0;
      for (size_t i = 0; i < got.size(); ++i) {
        d2 += (got[i] - exact[i]) * (got[i] - exact[i]);
        r2 += exact[i] * exact[i];
      }
      const double err = std::sqrt(d2 / r2);
      fmt::print("  {:<8} {:>12.3f} {:>10.2f} {:>14.3e}\n", b.name(), cells, s.median_ms, err);
      j.begin_object().field("backend", b.name()).field("path", "midpoint");
      j.field("step_cells", cells).field("ms", s.median_ms).field("rel_l2", err).end_object();
      progress.advance(fmt::format("{} midpoint {} cells", b.name(), cells));
    }
  });
  progress.finish();
  j.end_array();
  return rc;
}

}  // namespace

void add_light_bench(CLI::App& bench) {
  static LightBenchOptions o;
  auto* cmd = add_bench(bench, "light", "nebula lighting: thesis Table 2.3; path step vs error", o,
                        run_light_bench);
  add_table23_options(*cmd, o);
  add_ranged_option(*cmd, "--photons", o.photons, "photons per tau row of the table", 1u, 1u << 20);
  add_json_option(*cmd, o.json);
}

}  // namespace masav::app
