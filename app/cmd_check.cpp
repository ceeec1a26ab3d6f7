// `masav check`: runs Philox, the radix sort and the hash grid on the chosen backend and on the
// CPU reference with identical inputs, and requires bit-identical results.
#include <fmt/format.h>

#include <chrono>
#include <cstring>
#include <numeric>
#include <random>

#include "app/commands.h"
#include "engine/core/error.h"
#include "engine/cpu/cpu_backend.h"
#include "engine/grid/hash_grid.h"
#include "registry/backends.h"

namespace masav::app {
namespace {

struct Outcome {
  std::string name;
  bool pass;
  std::string detail;
};

template <class T>
size_t mismatches(const std::vector<T>& a, const std::vector<T>& b) {
  if (a.size() != b.size()) return std::max(a.size(), b.size());
  size_t m = 0;
  for (size_t i = 0; i < a.size(); ++i) m += std::memcmp(&a[i], &b[i], sizeof(T)) != 0;
  return m;
}

Outcome check_philox(Backend& b, Backend& r, uint32_t n) {
  auto x = b.create<uint32_t>(n, "philox"), y = r.create<uint32_t>(n, "philox");
  b.philox_u32({12345, 6, 0}, x);
  r.philox_u32({12345, 6, 0}, y);
  const size_t m = mismatches(b.download(x), r.download(y));
  return {"philox_u32", m == 0, fmt::format("{} words, {} differ", n, m)};
}

Outcome check_sort(Backend& b, Backend& r, uint32_t n, uint32_t bits) {
  std::mt19937 rng(bits);
  std::vector<uint32_t> keys(n), vals(n);
  for (auto& k : keys) k = rng();
  std::iota(vals.begin(), vals.end(), 0u);
  auto run = [&](Backend& be) {
    auto k = be.create<uint32_t>(n, "keys"), v = be.create<uint32_t>(n, "values");
    be.upload(k, keys);
    be.upload(v, vals);
    be.radix_sort({n, bits}, k, &v);
    return std::pair{be.download(k), be.download(v)};
  };
  const auto got = run(b), want = run(r);
  const size_t m = mismatches(got.first, want.first) + mismatches(got.second, want.second);
  return {fmt::format("radix_sort ({} bits)", bits), m == 0,
          fmt::format("{} pairs, {} differ", n, m)};
}

Outcome check_grid(Backend& b, Backend& r, uint32_t n) {
  std::mt19937 rng(77);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<Vec4f> pts(n);
  for (auto& p : pts) p = {u(rng), u(rng), u(rng), 0.0f};
  const GridParams gp = make_grid_params({0, 0, 0}, 1.0f / 32, {32, 32, 32}, n);
  struct Result {
    std::vector<uint32_t> cells, index, start, end, counts;
  };
  auto run = [&](Backend& be) {
    auto pos = be.create<Real4>(n, "positions");
    be.upload(pos, pts);
    HashGrid g = make_hash_grid(be, gp, n);
    build_hash_grid(be, g, pos);
    auto sorted = be.create<Real4>(n, "sorted");
    reorder(be, g, pos.impl(), sorted.impl());
    auto counts = be.create<uint32_t>(n, "counts");
    be.grid_count_neighbors(make_neighbor_params(gp, gp.cell_size), sorted, g.cell_start,
                            g.cell_end, counts);
    return Result{be.download(g.sorted_cells), be.download(g.sorted_index),
                  be.download(g.cell_start), be.download(g.cell_end), be.download(counts)};
  };
  const Result got = run(b), want = run(r);
  const size_t m = mismatches(got.cells, want.cells) + mismatches(got.index, want.index) +
                   mismatches(got.start, want.start) + mismatches(got.end, want.end);
  const size_t mc = mismatches(got.counts, want.counts);
  return {"hash_grid + neighbours", m == 0 && mc == 0,
          fmt::format("{} points in 32^3 cells: {} grid entries and {} neighbour counts differ", n,
                      m, mc)};
}

int run_check(const BackendChoice& choice) {
  auto backend = open_backend(choice);
  cpu::CpuBackend reference;
  fmt::print("self-check: {} ({}) against the CPU reference\n", backend->name(),
             backend->caps().device_name);
  const auto t0 = std::chrono::steady_clock::now();
  std::vector<Outcome> out = {
      check_philox(*backend, reference, 1 << 20), check_sort(*backend, reference, 1 << 20, 32),
      check_sort(*backend, reference, 1 << 20, 20), check_grid(*backend, reference, 200000)};
  bool all = true;
  for (const auto& o : out) {
    fmt::print("  {:<24} {}  {}\n", o.name, o.pass ? "PASS" : "FAIL", o.detail);
    all = all && o.pass;
  }
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  fmt::print("self-check {} in {:.2f} s\n", all ? "passed" : "FAILED", s);
  return all ? 0 : 1;
}

}  // namespace

void add_check_command(CLI::App& app) {
  static BackendChoice choice;
  auto* cmd = add_command(app, "check", "compare sort, grid and RNG against the CPU reference",
                          choice, run_check);
  add_backend_options(*cmd, choice, false);
}

}  // namespace masav::app
