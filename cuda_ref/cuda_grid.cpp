// The hash-grid kernels CUDA runs itself, host side: grid_cell_ranges clears the tables on the
// stream before its launch; gather picks the element size (grid_kernels.cu).
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
