// `masav bench sort`: key-value radix sort throughput per backend (and CUB on CUDA), timed with
// device timestamps; medians of repeated runs.
#include <fmt/format.h>

#include <numeric>
#include <random>

#include "app/bench_common.h"
#include "app/vocabulary.h"
#include "engine/core/error.h"

namespace masav::app {

struct SortBenchOptions : BenchOptions {
  uint32_t n = 1u << 24;
  uint32_t key_bits = 32;
  int reps = 5;
};

namespace {

int run_sort_bench(const SortBenchOptions& o, JsonWriter& j) {
  fmt::print("bench sort: {} key-value pairs, {} key bits, median of {} runs\n", o.n, o.key_bits,
             o.reps);
  std::mt19937 rng(1);
  const uint32_t mask = o.key_bits == 32 ? ~0u : (1u << o.key_bits) - 1;
  std::vector<uint32_t> keys(o.n), values(o.n);
  for (auto& k : keys) k = rng() & mask;
  std::iota(values.begin(), values.end(), 0u);

  j.field("n", o.n).field("key_bits", o.key_bits).key("rows").begin_array();
  int rc = 0;
  fmt::print("  {:<8} {:<10} {:<40} {:>10} {:>10} {:>12}\n", "backend", "impl", "device",
             "median ms", "min ms", "Mpairs/s");
  for (auto& b : open_backends(o.choice)) {
    std::vector<std::pair<std::string, SortImpl>> impls = {{"ours", SortImpl::portable}};
    if (b->name() == "cuda") impls.push_back({"cub", SortImpl::vendor});
    if (b->name() == "cpu") impls = {{"cpu-ref", SortImpl::portable}};
    for (const auto& [label, impl] : impls) {
      auto row = [&] {
        auto kb = b->create<uint32_t>(o.n, "keys");
        auto vb = b->create<uint32_t>(o.n, "values");
        const auto samples = time_on_device(
            *b, 1, o.reps, [&] { b->upload(kb, keys), b->upload(vb, values); },
            [&] {
              b->radix_sort({o.n, o.key_bits, impl}, kb, &vb);
            });
        const auto sorted = b->download(kb);
        bool verified = std::is_sorted(sorted.begin(), sorted.end());
        const TimingStats t = summarize(samples);
        const double rate = o.n / (t.median_ms * 1e-3);
        fmt::print("  {:<8} {:<10} {:<40.40} {:>10.3f} {:>10.3f} {:>12.1f}{}\n", b->name(), label,
                   b->caps().device_name, t.median_ms, t.min_ms, rate * 1e-6,
                   verified ? "" : "  NOT SORTED");
        begin_row(j, *b);
        j.field("impl", label).field("reps", t.reps).field("median_ms", t.median_ms);
        j.field("min_ms", t.min_ms).field("max_ms", t.max_ms).field("pairs_per_s", rate);
        j.field("verified_sorted", verified).end_object();
        if (!verified) rc = 1;
      };
      if (!run_row(fmt::format("{:<8} {:<10}", b->name(), label), row)) rc = 1;
    }
  }
  j.end_array();
  return rc;
}

}  // namespace

void add_sort_bench(CLI::App& bench) {
  static SortBenchOptions o;
  auto* cmd = add_bench(bench, "sort", "radix sort of key-value pairs", o, run_sort_bench);
  add_ranged_option(*cmd, "--pairs", o.n, "key-value pairs to sort", 1u, 1u << 28);
  add_old_option(*cmd, "--n", "--pairs", o.n)->check(CLI::Range(1u, 1u << 28));
  add_ranged_option(*cmd, "--key-bits", o.key_bits, "key bits in use (keys are masked to them)", 1u,
                    32u);
  add_reps_option(*cmd, o.reps);
  add_json_option(*cmd, o.json);
}

}  // namespace masav::app
