// Radix sort on CUDA, host side: our portable passes (histogram -> scan -> scatter) or CUB.
#include <fmt/format.h>

#include "cuda_ref/cuda_backend.h"
#include "cuda_ref/cuda_check.h"
#include "cuda_ref/cuda_launch.h"
#include "engine/core/error.h"
#include "engine/kernels/kernel_checks.h"
#include "engine/kernels/radix.h"

namespace masav::cuda {

// In-place exclusive prefix sum: scan tiles, then add each tile's offset: summed by the block
// itself from at most one tile of totals, else from the totals scanned recursively.
void CudaBackend::exclusive_scan(uint32_t* data, uint32_t count, const char* kernel,
                                 uint32_t level) {
  const uint32_t tiles = (count + launch::kSortTile - 1) / launch::kSortTile;
  auto* sums = static_cast<uint32_t*>(
      scratch(fmt::format("{} scan level {}", kernel, level), size_t(tiles) * 4, kernel));
  const dim3 grid = grid_for(tiles, kernel);
  const ScanParams scan{count, tiles};
  launched(launch::scan_tiles(stream_, grid, data, sums, scan), kernel, "scan_tiles");
  if (tiles > launch::kSortTile) {
    exclusive_scan(sums, tiles, kernel, level + 1);
    launched(launch::scan_add(stream_, grid, data, sums, scan), kernel, "scan_add");
  } else if (tiles > 1) {
    // At most one tile of totals: each block adds up those before it (as on Vulkan).
    launched(launch::scan_add_prefix(stream_, grid, data, sums, scan), kernel, "scan_add_prefix");
  }
}

void CudaBackend::sort_portable(uint32_t n, uint32_t key_bits, uint32_t* keys, uint32_t* values) {
  const uint32_t num_tiles = (n + launch::kSortTile - 1) / launch::kSortTile;
  auto* hist = static_cast<uint32_t*>(
      scratch("histogram", size_t(radix::kRadix) * num_tiles * 4, "radix_sort"));
  const uint32_t passes = radix::pass_count(key_bits);
  // Where each pass writes: radix::pass_buffer (an odd count of 3 or more ends home, no copy).
  auto scratch_pair = [&](const char* what) {
    auto* k =
        static_cast<uint32_t*>(scratch(fmt::format("keys{}", what), size_t(n) * 4, "radix_sort"));
    auto* v = values ? static_cast<uint32_t*>(
                           scratch(fmt::format("values{}", what), size_t(n) * 4, "radix_sort"))
                     : nullptr;
    return std::pair{k, v};
  };
  const std::pair home{keys, values};
  const auto a = scratch_pair("");
  const auto b = radix::uses_second_scratch(passes) ? scratch_pair(" 2") : a;
  std::pair src = home;
  const dim3 grid = grid_for(num_tiles, "radix_sort");
  for (uint32_t pass = 0; pass < passes; ++pass) {
    const auto dst = radix::pass_target(radix::pass_buffer(passes, pass), home, a, b);
    const RadixPassParams step{n, pass * radix::kDigitBits, radix::pass_bits(key_bits, pass),
                               num_tiles};
    launched(launch::radix_histogram(stream_, grid, src.first, hist, step), "radix_sort",
             "histogram");
    exclusive_scan(hist, (1u << step.bits) * num_tiles, "radix_sort");
    launched(launch::radix_scatter(stream_, grid, src.first, src.second, dst.first, dst.second,
                                   hist, step),
             "radix_sort", "scatter");
    src = dst;
  }
  if (src.first != keys) {  // a single pass: the result sits in scratch
    copy_device(keys, src.first, size_t(n) * 4, "radix_sort");
    if (values) copy_device(values, src.second, size_t(n) * 4, "radix_sort");
  }
}

void CudaBackend::sort_cub(uint32_t n, uint32_t key_bits, uint32_t* keys, uint32_t* values) {
  auto* k_alt = static_cast<uint32_t*>(scratch("keys", size_t(n) * 4, "radix_sort"));
  auto* v_alt =
      values ? static_cast<uint32_t*>(scratch("values", size_t(n) * 4, "radix_sort")) : nullptr;
  size_t temp_bytes = 0;
  bool in_alt = false;
  check(launch::cub_sort(stream_, nullptr, temp_bytes, keys, k_alt, values, v_alt, n, key_bits,
                         in_alt),
        "radix_sort", "cub sort (temporary size)");
  void* temp = scratch("cub temp", temp_bytes, "radix_sort");
  // Counted as one launch, though CUB queues several kernels and memsets (histogram, scan, one
  // kernel per 8-bit pass; one kernel for a small n), chosen per GPU and size out of our sight.
  launched(
      launch::cub_sort(stream_, temp, temp_bytes, keys, k_alt, values, v_alt, n, key_bits, in_alt),
      "radix_sort", "CUB DeviceRadixSort");
  if (in_alt) {
    copy_device(keys, k_alt, size_t(n) * 4, "radix_sort");
    if (values) copy_device(values, v_alt, size_t(n) * 4, "radix_sort");
  }
}

void CudaBackend::run_own(const KernelArgs<KernelId::radix_sort>& a) {
  auto& [p, items_, keys, values] = a;
  if (p.n <= 1) return;
  auto* k = static_cast<uint32_t*>(ptr(keys.impl(), "radix_sort"));
  auto* v = values ? static_cast<uint32_t*>(ptr(values->impl(), "radix_sort")) : nullptr;
  if (p.impl == SortImpl::vendor)
    sort_cub(p.n, p.key_bits, k, v);
  else
    sort_portable(p.n, p.key_bits, k, v);
}

}  // namespace masav::cuda
