// Portable LSD radix sort on Vulkan: per 8-bit pass, histogram -> exclusive scan -> scatter
// (reduce-then-scan; no workgroup ever waits on another, which lavapipe and mobile GPUs need).
// Two scatters: `tiled` sorts each tile in shared memory so writes go out in runs (GPUs);
// `subgroup` ranks keys with ballots and touches shared memory once per key (CPU devices,
// where every divergent shared access runs lane by lane).
#include <fmt/format.h>

#include "compute/vk_backend.h"
#include "engine/core/error.h"
#include "engine/kernels/kernel_checks.h"
#include "engine/kernels/radix.h"
#include "engine/kernels/sort_params.h"
#include "shaders/spec_ids.h"

namespace masav::vk {
namespace {

// Rounds of one subgroup per tile in the subgroup scatter: 2048 keys per tile at subgroup 8.
constexpr uint32_t kSubgroupRounds = 256;

}  // namespace

// In-place exclusive prefix sum of data[0..count): scan each tile, then add each tile's offset:
// summed by the tile itself from at most one tile of totals (scan_add_prefix), else from the
// totals scanned recursively (one level per factor of the tile size).
void VulkanBackend::exclusive_scan(const std::shared_ptr<Allocation>& data, uint32_t count,
                                   std::string_view kernel, uint32_t level) {
  const uint32_t tile = tile_size(), items = options_.items_per_thread;
  const uint32_t tiles = (count + tile - 1) / tile;
  auto sums = scratch(fmt::format("{} scan level {}", kernel, level), size_t(tiles) * 4);
  const ScanParams push{count, tiles};
  run({"scan_tiles", 2, sizeof push, {{kSpecItems, items}}}, {data, sums}, &push, tiles);
  if (tiles > tile) {
    exclusive_scan(sums, tiles, kernel, level + 1);
    run({"scan_add", 2, sizeof push, {{kSpecItems, items}}}, {data, sums}, &push, tiles);
  } else if (tiles > 1) {
    // At most one tile of totals: each tile adds up those before it itself (one dispatch
    // instead of a scan of the totals and then the add).
    run({"scan_add_prefix", 2, sizeof push, {{kSpecItems, items}}}, {data, sums}, &push, tiles);
  }
}

void VulkanBackend::run_own(const KernelArgs<KernelId::radix_sort>& args) {
  auto& [p, items_, keys, values] = args;
  if (p.n <= 1) return;
  // Tile geometry of the scatter variant; the histogram must use the same tiles.
  const bool by_subgroup = scatter_ == SortScatter::subgroup;
  const uint32_t wg = by_subgroup ? ctx_.caps().subgroup_size : options_.workgroup_size;
  const uint32_t items = by_subgroup ? kSubgroupRounds : options_.items_per_thread;
  const uint32_t tile = wg * items;
  const uint32_t num_tiles = (p.n + tile - 1) / tile;
  const uint64_t hist_entries = uint64_t(radix::kRadix) * num_tiles;
  check_fits(*this, ElemKind::u32, hist_entries, "radix_sort", "the digit histogram");
  const bool has_values = values != nullptr;

  std::shared_ptr<Allocation> k_home = alloc(keys.impl(), "radix_sort");
  std::shared_ptr<Allocation> v_home = has_values ? alloc(values->impl(), "radix_sort") : k_home;
  auto hist = scratch("radix_sort histogram", hist_entries * 4);
  const uint32_t passes = radix::pass_count(p.key_bits);
  // Where each pass writes (radix::pass_buffer): with an odd pass count of 3 or more, through a
  // second scratch pair so that the last pass lands home instead of a copy after it.
  const bool second = radix::uses_second_scratch(passes);
  auto scratch_pair = [&](const char* what) {
    std::shared_ptr<Allocation> k =
        scratch(fmt::format("radix_sort keys{}", what), size_t(p.n) * 4);
    std::shared_ptr<Allocation> v =
        has_values ? scratch(fmt::format("radix_sort values{}", what), size_t(p.n) * 4) : k;
    return std::pair{k, v};
  };
  const auto first_pair = scratch_pair("");
  const auto second_pair = second ? scratch_pair(" 2") : first_pair;
  const std::pair home{k_home, v_home};
  std::pair src = home;
  for (uint32_t pass = 0; pass < passes; ++pass) {
    const uint32_t bits = radix::pass_bits(p.key_bits, pass);
    const auto dst =
        radix::pass_target(radix::pass_buffer(passes, pass), home, first_pair, second_pair);
    const RadixPassParams push{p.n, pass * radix::kDigitBits, bits, num_tiles};
    run({"radix_histogram", 2, sizeof push, {{kSpecItems, items}}, wg}, {src.first, hist}, &push,
        num_tiles);
    exclusive_scan(hist, (1u << bits) * num_tiles, "radix_sort");
    run({by_subgroup ? "radix_scatter_subgroup" : "radix_scatter",
         5,
         sizeof push,
         {{kSpecItems, items}, {kSpecHasValues, has_values ? 1u : 0u}},
         wg},
        {src.first, src.second, dst.first, dst.second, hist}, &push, num_tiles);
    src = dst;
  }
  if (src.first != k_home) {  // a single pass: the result sits in scratch, copy it home
    stream_.copy(src.first, 0, k_home, 0, size_t(p.n) * 4);
    if (has_values) stream_.copy(src.second, 0, v_home, 0, size_t(p.n) * 4);
  }
}

}  // namespace masav::vk
