// The hash-grid kernels CUDA runs itself, host side: grid_cell_ranges clears the tables on the
// stream before its launch; grid_cell_offsets scans the counts (reduce-then-scan, with the
// sort's scan of the chunk sums); gather picks the element size (grid_kernels.cu).
#include <fmt/format.h>

#include "cuda_ref/cuda_backend.h"
#include "cuda_ref/cuda_launch.h"
#include "engine/core/error.h"

namespace masav::cuda {

void CudaBackend::run_own(const KernelArgs<KernelId::grid_cell_ranges>& a) {
  auto& [g, items_, sorted_cells, cell_start, cell_end] = a;
  const char* k = "grid_cell_ranges";
  auto* start = static_cast<uint32_t*>(ptr(cell_start.impl(), k));
  auto* end = static_cast<uint32_t*>(ptr(cell_end.impl(), k));
  zero(start, cell_start.impl().bytes(), k);
  zero(end, cell_end.impl().bytes(), k);
  if (!g.n) return;
  launched(
      launch::cell_ranges(stream_, grid_for_items(g.n, k), g,
                          static_cast<const uint32_t*>(ptr(sorted_cells.impl(), k)), start, end),
      k);
}

// Reduce-then-scan in chunks of kCellOffsetChunk cells, as on Vulkan (vk_grid.cpp): each
// chunk's sum, the sums scanned (the sort's exclusive scan), then each chunk from its offset.
void CudaBackend::run_own(const KernelArgs<KernelId::grid_cell_offsets>& a) {
  auto& [p, items_, counts, cell_start, cell_end] = a;
  const char* k = "grid_cell_offsets";
  const uint32_t chunks = (p.cell_count + kCellOffsetChunk - 1) / kCellOffsetChunk;
  auto* sums =
      static_cast<uint32_t*>(scratch("grid_cell_offsets chunk sums", size_t(chunks) * 4, k));
  const auto* count = static_cast<const uint32_t*>(ptr(counts.impl(), k));
  const ScanParams scan{p.cell_count, chunks};
  const dim3 grid = grid_for_items(chunks, k);
  launched(launch::chunk_sums(stream_, grid, scan, count, sums), k, "chunk_sums");
  exclusive_scan(sums, chunks, k);
  launched(launch::cell_offsets(stream_, grid, scan, count, sums,
                                static_cast<uint32_t*>(ptr(cell_start.impl(), k)),
                                static_cast<uint32_t*>(ptr(cell_end.impl(), k))),
           k, "cell_offsets");
}

void CudaBackend::run_own(const KernelArgs<KernelId::gather>& a) {
  auto& [p, items_, order, src, dst] = a;
  const size_t eb = elem_bytes(src.kind(), real_bytes());
  if (eb != 4 && eb != 16)
    throw Error("cuda", "gather", fmt::format("no gather for {}-byte elements", eb),
                "internal error: report it");
  launched(launch::gather(stream_, grid_for_items(p.n, "gather"),
                          device_params<float>(p, order, src, dst),
                          static_cast<const uint32_t*>(ptr(order.impl(), "gather")),
                          ptr(src, "gather"), ptr(dst, "gather"), uint32_t(eb), diag_),
           "gather");
}

}  // namespace masav::cuda
