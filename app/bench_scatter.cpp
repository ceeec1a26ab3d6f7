// `masav bench scatter`: the Monte Carlo scattering table (thesis §2.2.3, 1000 tau x 72 bins) on
// each backend -- time, photons/s, scattering events/s -- and run time against error: photons
// per tau row against a converged table and against the exact single-scattering limit.
#include <fmt/format.h>

#include <chrono>
#include <cmath>

#include "app/bench_atom_common.h"
#include "engine/atom/scatter_cache.h"
#include "engine/atom/scatter_reference.h"
#include "engine/core/error.h"
#include "engine/kernels/scatter_math.h"

namespace masav::app {

struct ScatterBenchOptions : BenchOptions {
  uint32_t photons = 1024;
  uint32_t reference_photons = 16384;
  int reps = 3;
};

namespace {

// Mean scattering events per photon, from 32 photons of every row traced on the host (double).
double mean_events(const ScatterTableParams& p) {
  double events = 0;
  uint64_t photons = 0;
  for (uint32_t r = 0; r < p.rows; ++r)
    for (uint32_t ph = 0; ph < std::min(p.photons_per_row, 32u); ++ph, ++photons)
      events += scatter::trace_photon<double>(p, double(p.first_row + r) * p.tau_step,
                                              scatter::photon_stream(p, r, ph))
                    .scatterings;
  return events / double(photons);
}

double table_error(const atom::ScatterTable& t, const atom::ScatterTable& ref) {
  const uint32_t stride = t.params.bins + kScatterExtras;
  double err = 0;
  for (uint32_t r = 0; r < t.params.rows; ++r)
    for (uint32_t b = 0; b < t.params.bins; ++b)
      err += std::abs(t.weight[r * stride + b] - ref.weight[r * stride + b]);
  return err / t.params.rows;  // mean L1 distance of a row's bins
}

int run_scatter_bench(const ScatterBenchOptions& o, JsonWriter& j) {
  ScatterTableParams p;  // thesis defaults: 1000 x 72, tau 0 .. 9.99, g = a = 0.6
  p.photons_per_row = o.photons;
  const double events = mean_events(p);
  fmt::print(
      "bench scatter: {} rows x {} bins, {} photons per row ({:.1f} scatterings per "
      "photon), median of {} runs\n",
      p.rows, p.bins, p.photons_per_row, events, o.reps);
  j.field("rows", p.rows).field("bins", p.bins).field("photons_per_row", p.photons_per_row);
  j.field("mean_scatterings_per_photon", events).key("rows_by_backend").begin_array();
  auto backends = open_backends(o.choice, "--photons 128 --reference-photons 2048");
  fmt::print("  {:<8} {:>11} {:>12} {:>14}\n", "backend", "median ms", "Mphotons/s", "Gevents/s");
  const uint64_t n = uint64_t(p.rows) * p.photons_per_row;
  int rc = for_each_backend(backends, [&](Backend& b) {
    const size_t entries = size_t(p.rows) * (p.bins + kScatterExtras);
    auto table = b.create<Real>(entries, "table");
    auto hits = b.create<uint32_t>(entries, "hits");
    const TimingStats s = time_work(b, o.reps, [&] { b.scatter_table(p, table, hits); });
    const double ps = n / (s.median_ms * 1e-3);
    fmt::print("  {:<8} {:>11.2f} {:>12.2f} {:>14.4f}\n", b.name(), s.median_ms, ps * 1e-6,
               ps * events * 1e-9);
    begin_row(j, b);
    j.field("median_ms", s.median_ms).field("min_ms", s.min_ms).field("max_ms", s.max_ms);
    j.field("photons_per_s", ps).field("events_per_s", ps * events).end_object();
  });
  j.end_array();
  // Run time against error on 100 rows (tau 0 .. 9.9): against a converged table, and at
  // tau = 0.05 with one scattering at most against the single-scattering quadrature.
  ScatterTableParams sw = p;
  sw.rows = 100;
  sw.tau_step = 0.1f;
  ScatterTableParams ss = p;
  ss.rows = 1;
  ss.first_row = 1;
  ss.tau_step = 0.05f;
  ss.max_scatterings = 1;
  ss.weight_threshold = 0;
  const auto quad = atom::single_scattering(double(ss.tau_step), ss.g, ss.bins);
  j.key("sweep").begin_array();
  fmt::print("  photons per row vs error (100 rows; reference {} photons per row):\n",
             o.reference_photons);
  fmt::print("  {:<8} {:>8} {:>10} {:>14} {:>16}\n", "backend", "photons", "ms", "L1 vs conv.",
             "L1 vs 1-scatter");
  rc |= for_each_backend(backends, [&](Backend& b) {
    ScatterTableParams rp = sw;
    rp.photons_per_row = o.reference_photons;
    rp.seed = 999;  // independent of the swept tables
    const atom::ScatterTable ref = atom::compute_scatter_table(b, rp);
    for (uint32_t photons : {64u, 256u, 1024u, 4096u}) {
      sw.photons_per_row = ss.photons_per_row = photons;
      const auto t0 = std::chrono::steady_clock::now();
      const atom::ScatterTable t = atom::compute_scatter_table(b, sw);
      const double ms =
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
      const atom::ScatterTable one = atom::compute_scatter_table(b, ss);
      double e1 = 0;
      for (uint32_t k = 0; k < ss.bins; ++k) {
        double w = one.weight[k];
        if (k + 1 == ss.bins) w -= one.weight[ss.bins + kScatterUnscattered];
        e1 += std::abs(w - ss.albedo * quad[k]);
      }
      const double ec = table_error(t, ref);
      fmt::print("  {:<8} {:>8} {:>10.2f} {:>14.3e} {:>16.3e}\n", b.name(), photons, ms, ec, e1);
      j.begin_object().field("backend", b.name()).field("photons_per_row", photons);
      j.field("ms", ms).field("l1_vs_converged", ec).field("l1_vs_single_scattering", e1);
      j.end_object();
    }
  });
  j.end_array();
  return rc;
}

}  // namespace

void add_scatter_bench(CLI::App& bench) {
  static ScatterBenchOptions o;
  auto* cmd = add_bench(bench, "scatter", "Monte Carlo scattering table; photons vs error", o,
                        run_scatter_bench);
  add_ranged_option(*cmd, "--photons", o.photons, "photons per tau row of the timed table", 1u,
                    1u << 20);
  add_ranged_option(*cmd, "--reference-photons", o.reference_photons,
                    "photons per row of the converged table", 64u, 1u << 20);
  add_reps_option(*cmd, o.reps);
  add_json_option(*cmd, o.json);
}

}  // namespace masav::app
