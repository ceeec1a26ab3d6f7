// `masav bench atom`: cloud creation (orbital_sample) for the thesis's Table 2.3 states and
// particle counts on each backend, beside the thesis's times; and run time against error:
// particle count against the error of the sampled moments <r>, <r^2> (closed forms).
#include <fmt/format.h>

#include <cmath>

#include "app/bench_atom_common.h"
#include "engine/atom/orbital_tables.h"
#include "engine/core/error.h"

namespace masav::app {

struct AtomBenchOptions : Table23Options {
  std::string sweep_state = "state6";
};

namespace {

// Samples the cloud of `t` (n particles) on `b`, `reps` timed runs after one warm-up; the last
// cloud is left in `pos`.
TimingStats time_sampling(Backend& b, const atom::OrbitalTables& t, uint32_t n, int reps,
                          Buffer<Real4>& pos) {
  auto tables = b.create<uint32_t>(t.cdf.size(), "tables");
  b.upload(tables, t.cdf);
  pos = b.create<Real4>(n, "positions");
  return time_work(b, reps, [&] { b.orbital_sample(t.params, tables, pos); });
}

int run_atom_bench(const AtomBenchOptions& o, JsonWriter& j) {
  fmt::print("bench atom: cloud creation for thesis Table 2.3 (counts x {}), median of {} runs\n",
             o.scale, o.reps);
  j.field("scale", o.scale).key("rows").begin_array();
  auto backends = open_backends(o.choice, "--scale 0.1");
  fmt::print("  {:<8} {:<8} {:>9} {:>11} {:>12} {:>11}\n", "backend", "state", "particles",
             "median ms", "Mparticles/s", "thesis s");
  int rc =
      for_each_thesis_row(backends, o.scale, [&](Backend& b, const ThesisRow& row, uint32_t n) {
        const auto t =
            atom::make_orbital_tables(atom::preset_state(row.state), OrbitalPlacement::exact, n, 1);
        Buffer<Real4> pos;
        const TimingStats s = time_sampling(b, t, n, o.reps, pos);
        fmt::print("  {:<8} {:<8} {:>9} {:>11.3f} {:>12.1f} {:>11.1f}\n", b.name(), row.state, n,
                   s.median_ms, n / (s.median_ms * 1e3), row.creation_s);
        begin_row(j, b);
        j.field("state", row.state).field("particles", n).field("median_ms", s.median_ms);
        j.field("min_ms", s.min_ms).field("max_ms", s.max_ms);
        j.field("thesis_creation_s", row.creation_s).end_object();
      });
  j.end_array();
  // Run time against error: the sampled <r> and <r^2> against the closed forms.
  const atom::OrbitalState st = atom::preset_state(o.sweep_state);
  fmt::print("  particle count vs moment error ({}, {}):\n", o.sweep_state, describe(st));
  fmt::print("  {:<8} {:>9} {:>10} {:>12} {:>12}\n", "backend", "particles", "ms", "|<r>| rel",
             "|<r^2>| rel");
  j.field("sweep_state", o.sweep_state).key("sweep").begin_array();
  for (auto& b : backends) {
    for (uint32_t n : {1000u, 10000u, 100000u, 1000000u}) {
      auto row = [&] {
        const auto t = atom::make_orbital_tables(st, OrbitalPlacement::exact, n, 77);
        Buffer<Real4> pos;
        const TimingStats s = time_sampling(*b, t, n, o.reps, pos);
        double r = 0, r2 = 0;
        for (const Vec4d& p : b->download(pos)) {
          const double rr = p.x * p.x + p.y * p.y + p.z * p.z;
          r += std::sqrt(rr);
          r2 += rr;
        }
        const double er = std::abs(r / n / atom::expect_r(st.n, st.l) - 1);
        const double er2 = std::abs(r2 / n / atom::expect_r2(st.n, st.l) - 1);
        fmt::print("  {:<8} {:>9} {:>10.3f} {:>12.2e} {:>12.2e}\n", b->name(), n, s.median_ms, er,
                   er2);
        j.begin_object().field("backend", b->name()).field("particles", n);
        j.field("median_ms", s.median_ms).field("rel_error_r", er).field("rel_error_r2", er2);
        j.end_object();
      };
      if (!run_row(backend_label(*b), row)) rc = 1;
    }
  }
  j.end_array();
  return rc;
}

}  // namespace

void add_atom_bench(CLI::App& bench) {
  static AtomBenchOptions o;
  auto* cmd = add_bench(bench, "atom", "cloud creation: thesis Table 2.3 states; count vs error", o,
                        run_atom_bench);
  add_table23_options(*cmd, o);
  cmd->add_option("--sweep-state", o.sweep_state, "state of the count-vs-error sweep")
      ->capture_default_str();
  add_json_option(*cmd, o.json);
}

}  // namespace masav::app
