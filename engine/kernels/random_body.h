#pragma once
// philox_u32 and philox_uniform: one 4-word Philox block per invocation (engine/kernels/philox.h).
// shaders/philox_u32.comp and philox_uniform.comp are the GLSL twins.
#include "engine/kernels/kernel_body.h"
#include "engine/kernels/philox.h"
#include "engine/kernels/random_params.h"

namespace masav {

namespace philox {
// Block `block` of the call's stream: words 4 block .. 4 block + 3 that lie below p.count.
template <class Out, class Word>
MASAV_HD inline void fill_block(uint32_t block, const PhiloxLayout& p, Out* out, Word&& word) {
  const Block r = stream_block(p.seed, p.stream, uint64_t(p.first_block) + block);
  for (uint32_t j = 0; j < 4; ++j) {
    const uint64_t i = 4 * uint64_t(block) + j;
    if (i < p.count) out[i] = word(r.w[j]);
  }
}
}  // namespace philox

template <>
struct KernelBody<KernelId::philox_u32> {
  static constexpr uint32_t kCpuGrain = 4096;
  template <class F, class Diag>
  MASAV_HD static void run(uint32_t block, const PhiloxLayout& p, Diag&, uint32_t* out) {
    philox::fill_block(block, p, out, [](uint32_t w) { return w; });
  }
};

template <>
struct KernelBody<KernelId::philox_uniform> {
  static constexpr uint32_t kCpuGrain = 4096;
  template <class F, class Diag>
  MASAV_HD static void run(uint32_t block, const PhiloxLayout& p, Diag&, float* out) {
    philox::fill_block(block, p, out, [](uint32_t w) { return philox::u01(w); });
  }
};

}  // namespace masav
