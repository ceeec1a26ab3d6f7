#pragma once
// The .cu side of the CUDA backend: kernels and their launchers, nothing else. Each launcher
// (cub_sort aside) launches one kernel and returns the launch status (cudaGetLastError); the host
// code (cuda_*.cpp, compiled by the C++ compiler) hands it to CudaBackend::launched, which checks
// and counts it.
#include <cuda_runtime_api.h>

#include <cstddef>
#include <cstdint>

#include "engine/kernels/grid_params.h"
#include "engine/kernels/sort_params.h"

namespace masav::cuda::launch {

constexpr uint32_t kBlock = 256;  // threads per block of the element-wise kernels
constexpr uint32_t kSortThreads = 256;
constexpr uint32_t kSortItems = 8;
constexpr uint32_t kSortTile = kSortThreads * kSortItems;  // < 65536 (16-bit packed counts)

// Diagnostics words: {max_loop_ticks, flags, detail, reserved}.
constexpr uint32_t kDiagWords = 4;

cudaError_t fill_u32(cudaStream_t s, dim3 grid, uint32_t* dst, size_t words, uint32_t value);

cudaError_t radix_histogram(cudaStream_t s, dim3 grid, const uint32_t* keys, uint32_t* hist,
                            RadixPassParams pass);
cudaError_t scan_tiles(cudaStream_t s, dim3 grid, uint32_t* data, uint32_t* sums, ScanParams scan);
cudaError_t scan_add(cudaStream_t s, dim3 grid, uint32_t* data, const uint32_t* sums,
                     ScanParams scan);
// scan_add for at most kSortTile tiles from the tiles' unscanned totals (one launch).
cudaError_t scan_add_prefix(cudaStream_t s, dim3 grid, uint32_t* data, const uint32_t* sums,
                            ScanParams scan);
cudaError_t radix_scatter(cudaStream_t s, dim3 grid, const uint32_t* keys_in,
                          const uint32_t* vals_in, uint32_t* keys_out, uint32_t* vals_out,
                          const uint32_t* offsets, RadixPassParams pass);
// CUB DeviceRadixSort over bits [0, key_bits). temp == nullptr queries temp_bytes. The result
// lies in the *_alt buffers when result_in_alt is set. vals may be null (keys only).
cudaError_t cub_sort(cudaStream_t s, void* temp, size_t& temp_bytes, uint32_t* keys,
                     uint32_t* keys_alt, uint32_t* vals, uint32_t* vals_alt, uint32_t n,
                     uint32_t key_bits, bool& result_in_alt);

cudaError_t cell_ranges(cudaStream_t s, dim3 grid, const GridParams& g, const uint32_t* cells,
                        uint32_t* start, uint32_t* end);
// grid_cell_offsets' passes over chunks of kCellOffsetChunk cells (scan.n cells, scan.num_tiles
// chunks): each chunk's sum, then each chunk scanned from its offset into the runs' two ends.
cudaError_t chunk_sums(cudaStream_t s, dim3 grid, const ScanParams& scan, const uint32_t* counts,
                       uint32_t* sums);
cudaError_t cell_offsets(cudaStream_t s, dim3 grid, const ScanParams& scan, const uint32_t* counts,
                         const uint32_t* chunk_offsets, uint32_t* start, uint32_t* end);
cudaError_t gather(cudaStream_t s, dim3 grid, const GatherLayout& p, const uint32_t* order,
                   const void* src, void* dst, uint32_t elem_bytes, uint32_t* diag);

}  // namespace masav::cuda::launch
