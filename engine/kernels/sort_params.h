// Parameters of radix_sort and of its passes (histogram, tile scan, scatter), shared by C++,
// CUDA and GLSL (engine/core/layout.h).
#ifndef MASAV_KERNELS_SORT_PARAMS_H
#define MASAV_KERNELS_SORT_PARAMS_H
#include "engine/core/layout.h"

MASAV_NAMESPACE_BEGIN

MASAV_ENUM_BEGIN(SortImpl)
MASAV_ENUMERATOR(SortImpl, portable, 0)  // our reduce-then-scan LSD sort (every backend)
MASAV_ENUMERATOR(SortImpl, vendor, 1)    // the vendor's (CUB on CUDA) where one exists
MASAV_ENUM_END(SortImpl)

// Stable LSD sort of keys[0..n) (and values[0..n) alongside) by the low `key_bits` bits of each
// key; bits above key_bits are ignored and kept.
MASAV_LAYOUT(RadixSortParams) {
  uint n MASAV_INIT(0u);
  uint key_bits MASAV_INIT(32u);
  MASAV_ENUM(SortImpl) impl MASAV_INIT(SortImpl::portable);
};

// One pass over `bits` bits from `shift` of n keys in num_tiles tiles (histogram and scatter).
MASAV_LAYOUT(RadixPassParams) {
  uint n;
  uint shift;
  uint bits;
  uint num_tiles;
};

// An exclusive scan of n words, in num_tiles tiles (scan_tiles, then scan_add).
MASAV_LAYOUT(ScanParams) {
  uint n;
  uint num_tiles;
};

MASAV_NAMESPACE_END

#ifdef __cplusplus
#include "engine/core/buffer.h"

namespace masav {

MASAV_LAYOUT_CHECK(RadixSortParams, 16, (n, 0), (key_bits, 4), (impl, 8))
MASAV_LAYOUT_CHECK(RadixPassParams, 16, (n, 0), (shift, 4), (bits, 8), (num_tiles, 12))
MASAV_LAYOUT_CHECK(ScanParams, 16, (n, 0), (num_tiles, 4))

class DeviceApi;
// Checked before any backend runs the kernel (engine/kernels/kernel_checks.cpp).
void validate(const DeviceApi& dev, const RadixSortParams& p, const Buffer<uint32_t>& keys,
              const Buffer<uint32_t>* values);

}  // namespace masav
#endif
#endif
