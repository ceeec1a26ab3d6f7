// The hash-grid kernels Vulkan runs itself: grid_cell_ranges clears the cell tables before its
// dispatch, and gather picks the shader of the element size (gather.glsl). Assignment and the
// neighbour count are single dispatches (vk_kernels.cpp).
#include <fmt/format.h>

#include "compute/vk_backend.h"
#include "engine/core/error.h"

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

void VulkanBackend::run_own(const KernelArgs<KernelId::gather>& a) {
  auto& [p, items_, order, src, dst] = a;
  const size_t eb = elem_bytes(src.kind(), real_bytes());
  if (eb != 4 && eb != 16)
    throw Error("vulkan", "gather", fmt::format("no gather for {}-byte elements", eb),
                "internal error: report it");
  const GatherLayout push = device_params<float>(p, order, src, dst);
  const uint32_t wg = options_.workgroup_size;
  run({eb == 16 ? "gather_u32x4" : "gather_u32", 3, sizeof push, {}},
      {alloc(order.impl(), "gather"), alloc(src, "gather"), alloc(dst, "gather")}, &push,
      (p.n + wg - 1) / wg, /*written: dst*/ 1u << 2);
}

}  // namespace masav::vk
