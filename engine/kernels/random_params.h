// Parameters of philox_u32 and philox_uniform: Philox4x32-10 (engine/kernels/philox.h). Shared
// by C++, CUDA and GLSL (engine/core/layout.h).
#ifndef MASAV_KERNELS_RANDOM_PARAMS_H
#define MASAV_KERNELS_RANDOM_PARAMS_H
#include "engine/core/layout.h"

MASAV_NAMESPACE_BEGIN

// What the kernels read: the stream of PhiloxParams and the words to write (the output's size).
MASAV_LAYOUT(PhiloxLayout) {
  MASAV_U64 seed;
  MASAV_U64 stream;
  MASAV_U64 first_block;
  uint count;
};

MASAV_NAMESPACE_END

#ifdef __cplusplus
#include "engine/core/buffer.h"

namespace masav {

MASAV_LAYOUT_CHECK(PhiloxLayout, 32, (seed, 0), (stream, 8), (first_block, 16), (count, 24))

// Philox4x32-10 stream: word i of the output is word (i % 4) of the block with counter
// (first_block + i / 4, stream) under key `seed`. Streams with different ids never overlap. The
// kernels fill their whole output buffer.
struct PhiloxParams {
  uint64_t seed = 0;
  uint64_t stream = 0;
  uint64_t first_block = 0;
};

template <class F, class Out>
PhiloxLayout device_params(const PhiloxParams& p, const Out& out) {
  return PhiloxLayout{p.seed, p.stream, p.first_block, uint32_t(out.size())};
}

class DeviceApi;
// Checked before any backend runs the kernel (engine/kernels/kernel_checks.cpp).
void validate(const DeviceApi& dev, const PhiloxParams& p, const Buffer<uint32_t>& out);
void validate(const DeviceApi& dev, const PhiloxParams& p, const Buffer<float>& out);

}  // namespace masav
#endif
#endif
