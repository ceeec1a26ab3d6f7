// Hash-grid kernels: thin launches around engine/kernels/grid_cell.h, the very functions the
// CPU reference runs.
#include "cuda_ref/cuda_launch.h"
#include "engine/core/kernel_checks.h"
#include "engine/kernels/grid_cell.h"

namespace masav::cuda::launch {
namespace {

__device__ uint64_t flat_thread() {
  return (uint64_t(blockIdx.y) * gridDim.x + blockIdx.x) * blockDim.x + threadIdx.x;
}

__device__ void report(uint32_t* diag, uint32_t flag, uint32_t detail) {
  atomicOr(&diag[1], flag);
  atomicMin(&diag[2], detail);
}

__global__ void assign_cells_kernel(GridArgs g, const float4* pos, uint32_t* cells,
                                    uint32_t* indices) {
  const uint64_t i = flat_thread();
  if (i >= g.n) return;
  const float4 p = pos[i];
  const grid::CellCoord c = grid::point_cell(p.x, p.y, p.z, g.origin, g.inv_cell, g.dims);
  cells[i] = grid::cell_id(c.x, c.y, c.z, g.dims[1], g.dims[2]);
  indices[i] = uint32_t(i);
}

__global__ void cell_ranges_kernel(const uint32_t* cells, uint32_t n, uint32_t* start,
                                   uint32_t* end) {
  const uint64_t i = flat_thread();
  if (i >= n) return;
  const uint32_t c = cells[i];
  if (i == 0 || cells[i - 1] != c) start[c] = uint32_t(i);
  if (i + 1 == n || cells[i + 1] != c) end[c] = uint32_t(i + 1);
}

template <class T>
__global__ void gather_kernel(const uint32_t* order, const T* src, T* dst, uint32_t n,
                              uint32_t src_count, uint32_t* diag) {
  const uint64_t i = flat_thread();
  if (i >= n) return;
  const uint32_t j = order[i];
  if (j >= src_count) {
    dst[i] = T{};
    report(diag, kDiagGatherIndexOutOfRange, uint32_t(i));
    return;
  }
  dst[i] = src[j];
}

__global__ void count_neighbors_kernel(GridArgs g, const float4* pos, const uint32_t* start,
                                       const uint32_t* end, float radius2,
                                       uint32_t max_candidates, uint32_t* counts, uint32_t* diag) {
  const uint64_t i = flat_thread();
  if (i >= g.n) return;
  auto pos_at = [pos](uint32_t j) {
    const float4 q = pos[j];
    return grid::Point3{q.x, q.y, q.z};
  };
  bool over = false;
  counts[i] = grid::count_neighbors(pos_at(uint32_t(i)), pos_at, g.origin, g.inv_cell, g.dims,
                                    start, end, radius2, max_candidates, over);
  if (over) report(diag, kDiagNeighborOverflow, uint32_t(i));
}

}  // namespace

cudaError_t assign_cells(cudaStream_t s, dim3 grid, GridArgs g, const float4* pos,
                         uint32_t* cells, uint32_t* indices) {
  assign_cells_kernel<<<grid, kBlock, 0, s>>>(g, pos, cells, indices);
  return cudaGetLastError();
}

cudaError_t cell_ranges(cudaStream_t s, dim3 grid, const uint32_t* cells, uint32_t n,
                        uint32_t* start, uint32_t* end) {
  cell_ranges_kernel<<<grid, kBlock, 0, s>>>(cells, n, start, end);
  return cudaGetLastError();
}

cudaError_t gather(cudaStream_t s, dim3 grid, const uint32_t* order, const void* src, void* dst,
                   uint32_t n, uint32_t src_count, uint32_t elem_bytes, uint32_t* diag) {
  if (elem_bytes == 16)
    gather_kernel<uint4><<<grid, kBlock, 0, s>>>(order, static_cast<const uint4*>(src),
                                                 static_cast<uint4*>(dst), n, src_count, diag);
  else if (elem_bytes == 4)
    gather_kernel<uint32_t><<<grid, kBlock, 0, s>>>(order, static_cast<const uint32_t*>(src),
                                                    static_cast<uint32_t*>(dst), n, src_count,
                                                    diag);
  else
    return cudaErrorInvalidValue;
  return cudaGetLastError();
}

cudaError_t count_neighbors(cudaStream_t s, dim3 grid, GridArgs g, const float4* pos,
                            const uint32_t* start, const uint32_t* end, float radius2,
                            uint32_t max_candidates, uint32_t* counts, uint32_t* diag) {
  count_neighbors_kernel<<<grid, kBlock, 0, s>>>(g, pos, start, end, radius2, max_candidates,
                                                 counts, diag);
  return cudaGetLastError();
}

}  // namespace masav::cuda::launch
