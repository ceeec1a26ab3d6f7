#pragma once
// Philox4x32-10 (Salmon et al., SC'11), the Random123 constants. Bit-identical on every backend:
// only 32-bit multiplies, xors and adds. The GLSL twin is shaders/common/philox.glsl.
#include <cstdint>

#include "engine/core/hd.h"

namespace masav::philox {

struct Block {
  uint32_t w[4];
};

constexpr uint32_t kM0 = 0xD2511F53u, kM1 = 0xCD9E8D57u;  // round multipliers
constexpr uint32_t kW0 = 0x9E3779B9u, kW1 = 0xBB67AE85u;  // key schedule (Weyl) increments

MASAV_HD inline Block philox4x32_10(Block ctr, uint32_t k0, uint32_t k1) {
  for (int round = 0; round < 10; ++round) {
    if (round > 0) {
      k0 += kW0;
      k1 += kW1;
    }
    const uint64_t p0 = uint64_t(kM0) * ctr.w[0];
    const uint64_t p1 = uint64_t(kM1) * ctr.w[2];
    const uint32_t hi0 = uint32_t(p0 >> 32), lo0 = uint32_t(p0);
    const uint32_t hi1 = uint32_t(p1 >> 32), lo1 = uint32_t(p1);
    ctr = Block{{hi1 ^ ctr.w[1] ^ k0, lo1, hi0 ^ ctr.w[3] ^ k1, lo0}};
  }
  return ctr;
}

// Block `block` of stream `stream` under `seed`: counter (block, stream), key seed.
MASAV_HD inline Block stream_block(uint64_t seed, uint64_t stream, uint64_t block) {
  return philox4x32_10(
      Block{{uint32_t(block), uint32_t(block >> 32), uint32_t(stream), uint32_t(stream >> 32)}},
      uint32_t(seed), uint32_t(seed >> 32));
}

// Uniform in [0, 1) from the top 24 bits: exact on every backend (no rounding mode involved).
MASAV_HD inline float u01(uint32_t word) { return float(word >> 8) * (1.0f / 16777216.0f); }

}  // namespace masav::philox
