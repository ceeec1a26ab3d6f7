// Radix sort kernels: our reduce-then-scan LSD sort, the same three steps as the Vulkan kernels
// (histogram -> scan -> stable tile scatter with 2-bit splits), and CUB's DeviceRadixSort.
#include <cub/device/device_radix_sort.cuh>

#include "cuda_ref/cuda_launch.h"
#include "engine/kernels/radix.h"

namespace masav::cuda::launch {
namespace {

constexpr uint32_t kThreads = kSortThreads, kItems = kSortItems, kTile = kSortTile;
constexpr uint32_t kWarps = kThreads / 32;

__device__ uint32_t flat_block() {
  return blockIdx.y * gridDim.x + blockIdx.x;
}

// Exclusive block-wide scan of a uint2 in thread order (warp shuffles, then warp totals).
// Ends with __syncthreads, so shared memory read before the call may be written after it.
__device__ uint2 block_exclusive_scan(uint2 v, uint2& total) {
  __shared__ uint2 warp_totals[kWarps];
  __shared__ uint2 block_total;
  const uint32_t lane = threadIdx.x % 32, warp = threadIdx.x / 32;
  uint2 inc = v;
  for (uint32_t d = 1; d < 32; d *= 2) {
    const uint32_t x = __shfl_up_sync(0xffffffffu, inc.x, d);
    const uint32_t y = __shfl_up_sync(0xffffffffu, inc.y, d);
    if (lane >= d) inc.x += x, inc.y += y;
  }
  if (lane == 31) warp_totals[warp] = inc;
  __syncthreads();
  if (threadIdx.x == 0) {
    uint2 acc = make_uint2(0, 0);
    for (uint32_t w = 0; w < kWarps; ++w) {
      const uint2 t = warp_totals[w];
      warp_totals[w] = acc;
      acc.x += t.x, acc.y += t.y;
    }
    block_total = acc;
  }
  __syncthreads();
  const uint2 base = warp_totals[warp];
  total = block_total;
  __syncthreads();
  return make_uint2(base.x + inc.x - v.x, base.y + inc.y - v.y);
}

__global__ void histogram_kernel(const uint32_t* keys, uint32_t* hist, RadixPassParams pass) {
  __shared__ uint32_t s_hist[radix::kRadix];
  const uint32_t tile = flat_block();
  if (tile >= pass.num_tiles) return;
  const uint32_t radix_size = 1u << pass.bits;
  for (uint32_t d = threadIdx.x; d < radix_size; d += kThreads) s_hist[d] = 0;
  __syncthreads();
  const uint32_t base = tile * kTile;
  for (uint32_t i = 0; i < kItems; ++i) {
    const uint32_t idx = base + i * kThreads + threadIdx.x;
    if (idx < pass.n) atomicAdd(&s_hist[radix::digit(keys[idx], pass.shift, pass.bits)], 1u);
  }
  __syncthreads();
  for (uint32_t d = threadIdx.x; d < radix_size; d += kThreads)
    hist[d * pass.num_tiles + tile] = s_hist[d];
}

__global__ void scan_tiles_kernel(uint32_t* data, uint32_t* sums, ScanParams scan) {
  __shared__ uint32_t s_data[kTile];
  const uint32_t tile = flat_block();
  if (tile >= scan.num_tiles) return;
  const uint32_t base = tile * kTile, valid = min(kTile, scan.n - base);
  for (uint32_t i = 0; i < kItems; ++i) {
    const uint32_t p = i * kThreads + threadIdx.x;
    s_data[p] = p < valid ? data[base + p] : 0u;
  }
  __syncthreads();
  uint32_t x[kItems], sum = 0;
  for (uint32_t i = 0; i < kItems; ++i) x[i] = s_data[threadIdx.x * kItems + i], sum += x[i];
  uint2 total;
  uint32_t prefix = block_exclusive_scan(make_uint2(sum, 0), total).x;
  for (uint32_t i = 0; i < kItems; ++i) s_data[threadIdx.x * kItems + i] = prefix, prefix += x[i];
  __syncthreads();
  for (uint32_t i = 0; i < kItems; ++i) {
    const uint32_t p = i * kThreads + threadIdx.x;
    if (p < valid) data[base + p] = s_data[p];
  }
  if (threadIdx.x == 0) sums[tile] = total.x;
}

__global__ void scan_add_kernel(uint32_t* data, const uint32_t* sums, ScanParams scan) {
  const uint32_t tile = flat_block();
  if (tile >= scan.num_tiles) return;
  const uint32_t add = sums[tile], base = tile * kTile;
  for (uint32_t i = 0; i < kItems; ++i) {
    const uint32_t p = base + i * kThreads + threadIdx.x;
    if (p < scan.n) data[p] += add;
  }
}

// scan_add where there are at most kTile tiles, from the unscanned tile totals: each block adds
// up the totals before its own (as shaders/scan_add_prefix.comp), one launch instead of two.
__global__ void scan_add_prefix_kernel(uint32_t* data, const uint32_t* sums, ScanParams scan) {
  const uint32_t tile = flat_block();
  if (tile >= scan.num_tiles) return;  // the whole block: no barrier is left waiting
  uint32_t before = 0;
  for (uint32_t k = threadIdx.x; k < tile; k += kThreads) before += sums[k];
  uint2 total;
  block_exclusive_scan(make_uint2(before, 0), total);
  const uint32_t add = total.x, base = tile * kTile;
  for (uint32_t i = 0; i < kItems; ++i) {
    const uint32_t p = base + i * kThreads + threadIdx.x;
    if (p < scan.n) data[p] += add;
  }
}

// One count in the 16-bit field of a 2-bit sub-digit: (sd0 | sd1 << 16, sd2 | sd3 << 16).
__device__ uint2 split_one(uint32_t sd) {
  return make_uint2(sd == 0 ? 1u : (sd == 1 ? 65536u : 0u), sd == 2 ? 1u : (sd == 3 ? 65536u : 0u));
}

template <bool kHasValues>
__global__ void scatter_kernel(const uint32_t* keys_in, const uint32_t* vals_in, uint32_t* keys_out,
                               uint32_t* vals_out, const uint32_t* offsets, RadixPassParams pass) {
  __shared__ uint32_t s_keys[kTile];
  __shared__ uint32_t s_vals[kHasValues ? kTile : 1];
  __shared__ uint32_t s_digit_start[radix::kRadix];
  const uint32_t tile = flat_block();
  if (tile >= pass.num_tiles) return;
  const uint32_t base = tile * kTile, valid = min(kTile, pass.n - base), rank = threadIdx.x;
  for (uint32_t i = 0; i < kItems; ++i) {
    const uint32_t p = i * kThreads + threadIdx.x;
    s_keys[p] = p < valid ? keys_in[base + p] : 0xFFFFFFFFu;  // padding sorts last (stable)
    if (kHasValues) s_vals[p] = p < valid ? vals_in[base + p] : 0u;
  }
  __syncthreads();
  uint32_t k[kItems], v[kItems];
  for (uint32_t i = 0; i < kItems; ++i) {
    k[i] = s_keys[rank * kItems + i];
    v[i] = kHasValues ? s_vals[rank * kItems + i] : 0u;
  }
  for (uint32_t b = 0; b < pass.bits; b += 2) {
    const uint32_t sh = pass.shift + b, mask = pass.bits - b >= 2 ? 3u : 1u;
    uint2 count = make_uint2(0, 0);
    for (uint32_t i = 0; i < kItems; ++i) {
      const uint2 one = split_one((k[i] >> sh) & mask);
      count.x += one.x, count.y += one.y;
    }
    uint2 total;
    const uint2 before = block_exclusive_scan(count, total);
    uint32_t run[4] = {before.x & 0xFFFFu, before.x >> 16, before.y & 0xFFFFu, before.y >> 16};
    const uint32_t t0 = total.x & 0xFFFFu, t1 = total.x >> 16, t2 = total.y & 0xFFFFu;
    const uint32_t start[4] = {0, t0, t0 + t1, t0 + t1 + t2};
    for (uint32_t i = 0; i < kItems; ++i) {
      const uint32_t sd = (k[i] >> sh) & mask, pos = start[sd] + run[sd]++;
      s_keys[pos] = k[i];
      if (kHasValues) s_vals[pos] = v[i];
    }
    __syncthreads();
    for (uint32_t i = 0; i < kItems; ++i) {
      k[i] = s_keys[rank * kItems + i];
      if (kHasValues) v[i] = s_vals[rank * kItems + i];
    }
  }
  for (uint32_t i = 0; i < kItems; ++i) {
    const uint32_t p = rank * kItems + i;
    if (p < valid) {
      const uint32_t d = radix::digit(k[i], pass.shift, pass.bits);
      if (p == 0 || radix::digit(s_keys[p - 1], pass.shift, pass.bits) != d) s_digit_start[d] = p;
    }
  }
  __syncthreads();
  for (uint32_t i = 0; i < kItems; ++i) {
    const uint32_t p = i * kThreads + threadIdx.x;
    if (p < valid) {
      const uint32_t key = s_keys[p], d = radix::digit(key, pass.shift, pass.bits);
      const uint32_t dst = offsets[d * pass.num_tiles + tile] + (p - s_digit_start[d]);
      keys_out[dst] = key;
      if (kHasValues) vals_out[dst] = s_vals[p];
    }
  }
}

}  // namespace

cudaError_t radix_histogram(cudaStream_t s, dim3 grid, const uint32_t* keys, uint32_t* hist,
                            RadixPassParams pass) {
  histogram_kernel<<<grid, kThreads, 0, s>>>(keys, hist, pass);
  return cudaGetLastError();
}

cudaError_t scan_tiles(cudaStream_t s, dim3 grid, uint32_t* data, uint32_t* sums, ScanParams scan) {
  scan_tiles_kernel<<<grid, kThreads, 0, s>>>(data, sums, scan);
  return cudaGetLastError();
}

cudaError_t scan_add(cudaStream_t s, dim3 grid, uint32_t* data, const uint32_t* sums,
                     ScanParams scan) {
  scan_add_kernel<<<grid, kThreads, 0, s>>>(data, sums, scan);
  return cudaGetLastError();
}

cudaError_t scan_add_prefix(cudaStream_t s, dim3 grid, uint32_t* data, const uint32_t* sums,
                            ScanParams scan) {
  scan_add_prefix_kernel<<<grid, kThreads, 0, s>>>(data, sums, scan);
  return cudaGetLastError();
}

cudaError_t radix_scatter(cudaStream_t s, dim3 grid, const uint32_t* keys_in,
                          const uint32_t* vals_in, uint32_t* keys_out, uint32_t* vals_out,
                          const uint32_t* offsets, RadixPassParams pass) {
  if (vals_in)
    scatter_kernel<true>
        <<<grid, kThreads, 0, s>>>(keys_in, vals_in, keys_out, vals_out, offsets, pass);
  else
    scatter_kernel<false>
        <<<grid, kThreads, 0, s>>>(keys_in, nullptr, keys_out, nullptr, offsets, pass);
  return cudaGetLastError();
}

cudaError_t cub_sort(cudaStream_t s, void* temp, size_t& temp_bytes, uint32_t* keys,
                     uint32_t* keys_alt, uint32_t* vals, uint32_t* vals_alt, uint32_t n,
                     uint32_t key_bits, bool& result_in_alt) {
  cub::DoubleBuffer<uint32_t> kb(keys, keys_alt);
  cudaError_t st;
  if (vals) {
    cub::DoubleBuffer<uint32_t> vb(vals, vals_alt);
    st = cub::DeviceRadixSort::SortPairs(temp, temp_bytes, kb, vb, n, 0, int(key_bits), s);
  } else {
    st = cub::DeviceRadixSort::SortKeys(temp, temp_bytes, kb, n, 0, int(key_bits), s);
  }
  result_in_alt = kb.selector != 0;  // keys and values flip together
  return st;
}

}  // namespace masav::cuda::launch
