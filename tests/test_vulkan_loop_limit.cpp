// lavapipe silently stops a shader invocation after 65,535 loop iterations (PLATFORM.md). Every
// kernel is built here with loop counting on and driven at its worst case; the largest count
// any invocation reached must stay below the limit. Vulkan only: exits 77 without a device.
#define DOCTEST_CONFIG_IMPLEMENT
#include <doctest/doctest.h>
#include <fmt/format.h>

#include <memory>
#include <numeric>
#include <random>
#include <vector>

#include "compute/vk_backend.h"
#include "compute/vk_factory.h"
#include "engine/error.h"
#include "engine/hash_grid.h"

using namespace masav;
namespace mvk = masav::vk;

namespace {

constexpr uint32_t kLavapipeLoopLimit = 65535;
std::unique_ptr<mvk::VulkanBackend> g_vk;

std::vector<Vec4f> cluster(uint32_t n, float extent, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, extent);
  std::vector<Vec4f> p(n);
  for (auto& v : p) v = {u(rng), u(rng), u(rng), 0.0f};
  return p;
}

}  // namespace

TEST_CASE("philox kernels loop a fixed, small number of times") {
  auto& b = *g_vk;
  auto out = b.create<uint32_t>(1 << 16, "words");
  b.philox_u32({1, 2, 3}, out);
  const uint32_t ticks = b.take_max_loop_ticks();
  CHECK(ticks == 10 + 4);  // ten rounds, four output words
}

TEST_CASE("radix sort and its scans stay far below the loop limit at 2^20 keys") {
  auto& b = *g_vk;
  const uint32_t n = 1 << 20;
  std::vector<uint32_t> keys(n);
  std::mt19937 rng(5);
  for (auto& k : keys) k = rng();
  auto kb = b.create<uint32_t>(n, "keys");
  auto vb = b.create<uint32_t>(n, "values");
  b.upload(kb, keys);
  b.radix_sort({n, 32}, kb, &vb);
  const uint32_t ticks = b.take_max_loop_ticks();
  MESSAGE("radix_sort worst invocation: " << ticks << " loop iterations");
  CHECK(ticks > 0);
  // Independent of n. Tiled scatter: a few loops over the tile and the subgroups (~300).
  // Subgroup scatter: the digit table (256 / subgroup) plus 256 rounds of 1 + 8 ballot steps.
  CHECK(ticks <= 256 / 4 + 256 * 9);
}

TEST_CASE("neighbour count: loop ticks = 27 cells + candidates, capped below the limit") {
  auto& b = *g_vk;
  const uint32_t n = 4000;
  const GridParams gp = make_grid_params({0, 0, 0}, 1.0f, {1, 1, 1}, n);  // one crowded cell
  auto pos = b.create<Real4>(n, "pos");
  b.upload(pos, cluster(n, 1.0f, 9));
  HashGrid g = make_hash_grid(b, gp, n);
  build_hash_grid(b, g, pos);
  (void)b.take_max_loop_ticks();
  auto counts = b.create<uint32_t>(n, "counts");
  NeighborParams np = make_neighbor_params(gp, 1.0f);
  np.max_candidates = n;
  b.grid_count_neighbors(np, pos, g.cell_start, g.cell_end, counts);
  CHECK(b.take_max_loop_ticks() == 27 + n);  // the counter measures what we think it does
  // The validated maximum of max_candidates keeps the worst invocation under the limit.
  NeighborParams worst = np;
  worst.max_candidates = 65000;
  CHECK(27 + worst.max_candidates + 1 < kLavapipeLoopLimit);
  worst.max_candidates = 65001;
  CHECK_THROWS_AS(b.grid_count_neighbors(worst, pos, g.cell_start, g.cell_end, counts), Error);
}

TEST_CASE("grid assignment, ranges and gather do not loop") {
  auto& b = *g_vk;
  const uint32_t n = 100000;
  const GridParams gp = make_grid_params({0, 0, 0}, 0.05f, {20, 20, 20}, n);
  auto pos = b.create<Real4>(n, "pos");
  b.upload(pos, cluster(n, 1.0f, 4));
  HashGrid g = make_hash_grid(b, gp, n);
  b.grid_assign_cells(gp, pos, g.sorted_cells, g.sorted_index);
  CHECK(b.take_max_loop_ticks() == 0);
  b.radix_sort({n, grid_key_bits(gp)}, g.sorted_cells, &g.sorted_index);
  (void)b.take_max_loop_ticks();
  b.grid_cell_ranges(gp, g.sorted_cells, g.cell_start, g.cell_end);
  auto sorted = b.create<Real4>(n, "sorted");
  reorder(b, g, pos.impl(), sorted.impl());
  CHECK(b.take_max_loop_ticks() == 0);
}

TEST_CASE("drift_points loops three times (one per axis), independent of n") {
  auto& b = *g_vk;
  const uint32_t n = 100000;
  auto start = b.create<float>(4 * n, "start");
  auto dir = b.create<float>(4 * n, "direction");
  auto pos = b.create<Real4>(n, "positions");
  b.philox_uniform({1, 0, 0}, start);
  b.philox_uniform({1, 1, 0}, dir);
  (void)b.take_max_loop_ticks();
  DriftParams p;
  p.n = n;
  p.time_s = 100.0f;
  b.drift_points(p, start, dir, pos);
  CHECK(b.take_max_loop_ticks() == 3);
}

int main(int argc, char** argv) {
  const BackendStatus s = mvk::backend_status();
  if (!s.available) {
    fmt::print("SKIPPED: Vulkan is not available here: {}\n", s.reason);
    return 77;
  }
  mvk::set_validation_handler([](const std::string& msg) {
    if (doctest::is_running_in_test) FAIL_CHECK(msg);
    else fmt::print(stderr, "{}\n", msg);
  });
  mvk::BackendOptions o;
  o.context = mvk::options_from_env();
  o.count_loop_ticks = true;
  g_vk = std::make_unique<mvk::VulkanBackend>(o);
  fmt::print("loop-limit tests on {}\n", g_vk->caps().device_name);
  doctest::Context ctx(argc, argv);
  const int rc = ctx.run();
  g_vk.reset();
  return rc;
}
