#pragma once
// Digit arithmetic of the LSD radix sort, shared by every backend's sort.
#include <cstdint>

#include "engine/core/hd.h"

namespace masav::radix {

constexpr uint32_t kDigitBits = 8;  // bits sorted per pass
constexpr uint32_t kRadix = 1u << kDigitBits;

MASAV_HD inline uint32_t pass_count(uint32_t key_bits) {
  return (key_bits + kDigitBits - 1) / kDigitBits;
}
MASAV_HD inline uint32_t pass_bits(uint32_t key_bits, uint32_t pass) {
  const uint32_t left = key_bits - pass * kDigitBits;
  return left < kDigitBits ? left : kDigitBits;
}
MASAV_HD inline uint32_t digit(uint32_t key, uint32_t shift, uint32_t bits) {
  return (key >> shift) & ((1u << bits) - 1u);
}

}  // namespace masav::radix
