// The hash-grid kernels CUDA runs itself: cell ranges (after the host clears the tables), the
// chunk passes of grid_cell_offsets (the host scans the chunk sums between them) and gather of
// 4- or 16-byte elements. The per-point grid kernels run their shared bodies
// (engine/kernels/grid_body.h, cuda_kernels.cu).
#include "cuda_ref/cuda_launch.h"

namespace masav::cuda::launch {
namespace {

__device__ uint64_t flat_thread() {
  return (uint64_t(blockIdx.y) * gridDim.x + blockIdx.x) * blockDim.x + threadIdx.x;
}

__global__ void cell_ranges_kernel(GridParams g, const uint32_t* cells, uint32_t* start,
                                   uint32_t* end) {
  const uint64_t i = flat_thread();
  if (i >= g.n) return;
  const uint32_t c = cells[i];
  if (i == 0 || cells[i - 1] != c) start[c] = uint32_t(i);
  if (i + 1 == g.n || cells[i + 1] != c) end[c] = uint32_t(i + 1);
}

// grid_cell_offsets' passes, one thread per chunk of kCellOffsetChunk consecutive cells (the twins
// of shaders/scan_chunk_sums.comp and shaders/grid_cell_offsets.comp).
__global__ void chunk_sums_kernel(ScanParams scan, const uint32_t* counts, uint32_t* sums) {
  const uint64_t chunk = flat_thread();
  if (chunk >= scan.num_tiles) return;
  const uint32_t base = uint32_t(chunk) * kCellOffsetChunk;
  const uint32_t size = min(kCellOffsetChunk, scan.n - base);
  uint32_t sum = 0;
  for (uint32_t i = 0; i < size; ++i) sum += counts[base + i];
  sums[chunk] = sum;
}

__global__ void cell_offsets_kernel(ScanParams scan, const uint32_t* counts,
                                    const uint32_t* chunk_offsets, uint32_t* start, uint32_t* end) {
  const uint64_t chunk = flat_thread();
  if (chunk >= scan.num_tiles) return;
  const uint32_t base = uint32_t(chunk) * kCellOffsetChunk;
  const uint32_t size = min(kCellOffsetChunk, scan.n - base);
  uint32_t at = chunk_offsets[chunk];
  for (uint32_t i = 0; i < size; ++i) {
    start[base + i] = at;
    at += counts[base + i];
    end[base + i] = at;
  }
}

template <class T>
__global__ void gather_kernel(GatherLayout p, const uint32_t* order, const T* src, T* dst,
                              uint32_t* diag) {
  const uint64_t i = flat_thread();
  if (i >= p.n) return;
  const uint32_t j = order[i];
  if (j >= p.src_count) {
    dst[i] = T{};
    atomicOr(&diag[1], kDiagGatherIndexOutOfRange);
    atomicMin(&diag[2], uint32_t(i));
    return;
  }
  dst[i] = src[j];
}

}  // namespace

cudaError_t cell_ranges(cudaStream_t s, dim3 grid, const GridParams& g, const uint32_t* cells,
                        uint32_t* start, uint32_t* end) {
  cell_ranges_kernel<<<grid, kBlock, 0, s>>>(g, cells, start, end);
  return cudaGetLastError();
}

cudaError_t chunk_sums(cudaStream_t s, dim3 grid, const ScanParams& scan, const uint32_t* counts,
                       uint32_t* sums) {
  chunk_sums_kernel<<<grid, kBlock, 0, s>>>(scan, counts, sums);
  return cudaGetLastError();
}

cudaError_t cell_offsets(cudaStream_t s, dim3 grid, const ScanParams& scan, const uint32_t* counts,
                         const uint32_t* chunk_offsets, uint32_t* start, uint32_t* end) {
  cell_offsets_kernel<<<grid, kBlock, 0, s>>>(scan, counts, chunk_offsets, start, end);
  return cudaGetLastError();
}

cudaError_t gather(cudaStream_t s, dim3 grid, const GatherLayout& p, const uint32_t* order,
                   const void* src, void* dst, uint32_t elem_bytes, uint32_t* diag) {
  if (elem_bytes == 16)
    gather_kernel<uint4><<<grid, kBlock, 0, s>>>(p, order, static_cast<const uint4*>(src),
                                                 static_cast<uint4*>(dst), diag);
  else if (elem_bytes == 4)
    gather_kernel<uint32_t><<<grid, kBlock, 0, s>>>(p, order, static_cast<const uint32_t*>(src),
                                                    static_cast<uint32_t*>(dst), diag);
  else
    return cudaErrorInvalidValue;
  return cudaGetLastError();
}

}  // namespace masav::cuda::launch
