// Hash-grid kernels on CUDA, host side: checks, then the launches in grid_kernels.cu.
#include <fmt/format.h>

#include "cuda_ref/cuda_backend.h"
#include "cuda_ref/cuda_check.h"
#include "cuda_ref/cuda_launch.h"
#include "engine/core/error.h"
#include "engine/core/kernel_checks.h"

namespace masav::cuda {
namespace {

launch::GridArgs grid_args(const GridParams& g) {
  return launch::GridArgs{{g.origin.x, g.origin.y, g.origin.z}, g.inv_cell,
                          {g.dims.x, g.dims.y, g.dims.z}, g.n};
}

}  // namespace

void CudaBackend::do_grid_assign_cells(const GridParams& g, uint64_t, const Buffer<Real4>& positions,
                                    Buffer<uint32_t>& cells, Buffer<uint32_t>& indices) {
  check(launch::assign_cells(stream_, grid_for_items(g.n, "grid_assign_cells"), grid_args(g),
                             static_cast<const float4*>(ptr(positions.impl(), "grid_assign_cells")),
                             static_cast<uint32_t*>(ptr(cells.impl(), "grid_assign_cells")),
                             static_cast<uint32_t*>(ptr(indices.impl(), "grid_assign_cells"))),
        "grid_assign_cells", "launch");
}

void CudaBackend::do_grid_cell_ranges(const GridParams& g, uint64_t, const Buffer<uint32_t>& sorted_cells,
                                   Buffer<uint32_t>& cell_start, Buffer<uint32_t>& cell_end) {
  auto* start = static_cast<uint32_t*>(ptr(cell_start.impl(), "grid_cell_ranges"));
  auto* end = static_cast<uint32_t*>(ptr(cell_end.impl(), "grid_cell_ranges"));
  check(cudaMemsetAsync(start, 0, cell_start.impl().bytes(), stream_), "grid_cell_ranges",
        "cudaMemsetAsync");
  check(cudaMemsetAsync(end, 0, cell_end.impl().bytes(), stream_), "grid_cell_ranges",
        "cudaMemsetAsync");
  if (!g.n) return;
  check(launch::cell_ranges(stream_, grid_for_items(g.n, "grid_cell_ranges"),
                            static_cast<const uint32_t*>(ptr(sorted_cells.impl(), "grid_cell_ranges")),
                            g.n, start, end),
        "grid_cell_ranges", "launch");
}

void CudaBackend::do_gather(const GatherParams& p, uint64_t, const Buffer<uint32_t>& order,
                            const BufferImpl& src, BufferImpl& dst) {
  const uint32_t n = p.n;
  const size_t eb = elem_bytes(src.kind(), real_bytes());
  if (eb != 4 && eb != 16)
    throw Error("cuda", "gather", fmt::format("no gather for {}-byte elements", eb),
                "internal error: report it");
  check(launch::gather(stream_, grid_for_items(n, "gather"),
                       static_cast<const uint32_t*>(ptr(order.impl(), "gather")), ptr(src, "gather"),
                       ptr(dst, "gather"), n, uint32_t(src.count()), uint32_t(eb), diag_),
        "gather", "launch");
}

void CudaBackend::do_grid_count_neighbors(const NeighborParams& p, uint64_t,
                                       const Buffer<Real4>& sorted_positions,
                                       const Buffer<uint32_t>& cell_start,
                                       const Buffer<uint32_t>& cell_end,
                                       Buffer<uint32_t>& counts) {
  pending_neighbor_limit_ = p.max_candidates;
  const char* k = "grid_count_neighbors";
  check(launch::count_neighbors(stream_, grid_for_items(p.grid.n, k), grid_args(p.grid),
                                static_cast<const float4*>(ptr(sorted_positions.impl(), k)),
                                static_cast<const uint32_t*>(ptr(cell_start.impl(), k)),
                                static_cast<const uint32_t*>(ptr(cell_end.impl(), k)), p.radius2,
                                p.max_candidates, static_cast<uint32_t*>(ptr(counts.impl(), k)),
                                diag_),
        k, "launch");
}

}  // namespace masav::cuda
