// Hash-grid kernels on Vulkan: cell assignment, cell ranges, gather (reorder) and the 27-cell
// neighbour count. The sort between assignment and ranges is radix_sort.
#include <fmt/format.h>

#include "compute/vk_backend.h"
#include "engine/core/error.h"
#include "engine/core/kernel_checks.h"

namespace masav::vk {
namespace {

struct GridPush {
  float origin_inv_cell[4];
  uint32_t dims_n[4];
};
struct NeighborPush {
  GridPush grid;
  float radius2;
  uint32_t max_candidates;
};
struct GatherPush {
  uint32_t n, src_count;
};

GridPush grid_push(const GridParams& g) {
  return GridPush{{g.origin.x, g.origin.y, g.origin.z, g.inv_cell},
                  {g.dims.x, g.dims.y, g.dims.z, g.n}};
}

uint64_t groups_for(uint64_t items, uint32_t wg) { return (items + wg - 1) / wg; }

}  // namespace

void VulkanBackend::do_grid_assign_cells(const GridParams& g, uint64_t, const Buffer<Real4>& positions,
                                      Buffer<uint32_t>& cells, Buffer<uint32_t>& indices) {
  const GridPush push = grid_push(g);
  run({"grid_assign_cells", 3, sizeof push, {}},
      {alloc(positions.impl(), "grid_assign_cells"), alloc(cells.impl(), "grid_assign_cells"),
       alloc(indices.impl(), "grid_assign_cells")},
      &push, groups_for(g.n, options_.workgroup_size));
}

void VulkanBackend::do_grid_cell_ranges(const GridParams& g, uint64_t, const Buffer<uint32_t>& sorted_cells,
                                     Buffer<uint32_t>& cell_start, Buffer<uint32_t>& cell_end) {
  const auto& start = alloc(cell_start.impl(), "grid_cell_ranges");
  const auto& end = alloc(cell_end.impl(), "grid_cell_ranges");
  stream_.fill(start, 0);
  stream_.fill(end, 0);
  const uint32_t push = g.n;
  run({"grid_cell_ranges", 3, sizeof push, {}},
      {alloc(sorted_cells.impl(), "grid_cell_ranges"), start, end}, &push,
      groups_for(g.n, options_.workgroup_size));
}

void VulkanBackend::do_gather(const GatherParams& p, uint64_t, const Buffer<uint32_t>& order,
                              const BufferImpl& src, BufferImpl& dst) {
  const size_t eb = elem_bytes(src.kind(), real_bytes());
  const GatherPush push{p.n, uint32_t(src.count())};
  const char* shader = eb == 16 ? "gather_u32x4" : "gather_u32";
  if (eb != 4 && eb != 16)
    throw Error("vulkan", "gather", fmt::format("no gather for {}-byte elements", eb),
                "internal error: report it");
  run({shader, 3, sizeof push, {}},
      {alloc(order.impl(), "gather"), alloc(src, "gather"), alloc(dst, "gather")}, &push,
      groups_for(p.n, options_.workgroup_size));
}

void VulkanBackend::do_grid_count_neighbors(const NeighborParams& p, uint64_t,
                                         const Buffer<Real4>& sorted_positions,
                                         const Buffer<uint32_t>& cell_start,
                                         const Buffer<uint32_t>& cell_end,
                                         Buffer<uint32_t>& counts) {
  const NeighborPush push{grid_push(p.grid), p.radius2, p.max_candidates};
  pending_neighbor_limit_ = p.max_candidates;
  run({"grid_count_neighbors", 4, sizeof push, {}},
      {alloc(sorted_positions.impl(), "grid_count_neighbors"),
       alloc(cell_start.impl(), "grid_count_neighbors"),
       alloc(cell_end.impl(), "grid_count_neighbors"), alloc(counts.impl(), "grid_count_neighbors")},
      &push, groups_for(p.grid.n, options_.workgroup_size));
}

}  // namespace masav::vk
