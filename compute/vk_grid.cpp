// The hash-grid kernels Vulkan runs itself: grid_cell_ranges clears the cell tables before its
// dispatch, grid_cell_offsets scans the counts (reduce-then-scan, with the sort's scan of the
// chunk sums), and gather picks the shader of the element size (gather.glsl). The other grid
// kernels are single dispatches (vk_kernels.cpp).
#include <fmt/format.h>

#include "compute/vk_backend.h"
#include "engine/core/error.h"
#include "engine/kernels/sort_params.h"

namespace masav::vk {

void VulkanBackend::run_own(const KernelArgs<KernelId::grid_cell_ranges>& a) {
  auto& [g, items_, sorted_cells, cell_start, cell_end] = a;
  const auto& start = alloc(cell_start.impl(), "grid_cell_ranges");
  const auto& end = alloc(cell_end.impl(), "grid_cell_ranges");
  stream_.fill(start, 0);
  stream_.fill(end, 0);
  if (g.n == 0) return;
  const uint32_t wg = options_.workgroup_size;
  run({"grid_cell_ranges", 3, sizeof g, {}},
      {alloc(sorted_cells.impl(), "grid_cell_ranges"), start, end}, &g, (g.n + wg - 1) / wg);
}

// Reduce-then-scan in chunks of kCellOffsetChunk cells (grid_params.h): each chunk's sum, the
// sums scanned (the sort's exclusive scan), then each chunk scanned from its offset. The counts
// are read twice and the ends written once.
void VulkanBackend::run_own(const KernelArgs<KernelId::grid_cell_offsets>& a) {
  auto& [p, items_, counts, cell_start, cell_end] = a;
  const char* k = "grid_cell_offsets";
  const uint32_t chunks = (p.cell_count + kCellOffsetChunk - 1) / kCellOffsetChunk;
  auto sums = scratch("grid_cell_offsets chunk sums", size_t(chunks) * 4);
  const ScanParams push{p.cell_count, chunks};
  const auto& c = alloc(counts.impl(), k);
  const uint32_t wg = options_.workgroup_size, groups = (chunks + wg - 1) / wg;
  run({"scan_chunk_sums", 2, sizeof push, {}}, {c, sums}, &push, groups);
  exclusive_scan(sums, chunks, k);
  run({k, 4, sizeof push, {}}, {c, sums, alloc(cell_start.impl(), k), alloc(cell_end.impl(), k)},
      &push, groups);
}

void VulkanBackend::run_own(const KernelArgs<KernelId::gather>& a) {
  auto& [p, items_, order, src, dst] = a;
  const size_t eb = elem_bytes(src.kind(), real_bytes());
  if (eb != 4 && eb != 16)
    throw Error("vulkan", "gather", fmt::format("no gather for {}-byte elements", eb),
                "internal error: report it");
  const GatherLayout push = device_params<float>(p, order, src, dst);
  const uint32_t wg = options_.workgroup_size;
  const Texels words = eb == 16 ? kTexelsRgba32u : kTexelsR32u;
  run({eb == 16 ? "gather_u32x4" : "gather_u32",
       3,
       sizeof push,
       {},
       0,
       {kTexelsR32u, words, kStorageBuffer}},
      {alloc(order.impl(), "gather"), alloc(src, "gather"), alloc(dst, "gather")}, &push,
      (p.n + wg - 1) / wg, /*written: dst*/ 1u << 2);
}

}  // namespace masav::vk
