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

// The buffer pass `pass` of `passes` writes; pass 0 reads home (the caller's keys), every later
// pass the one before's. An even count alternates a, home, ..., a, home; an odd count of 3 or
// more writes a, b, a, ..., b, home, so the result lands home without a copy, at the cost of a
// second scratch pair (uses_second_scratch); a single pass writes a, and the caller copies it home.
enum class PassBuffer { home, a, b };
inline PassBuffer pass_buffer(uint32_t passes, uint32_t pass) {
  if (passes % 2 == 0) return pass % 2 == 0 ? PassBuffer::a : PassBuffer::home;
  if (passes == 1) return PassBuffer::a;
  if (pass + 1 == passes) return PassBuffer::home;
  return pass % 2 == 0 ? PassBuffer::a : PassBuffer::b;
}
inline bool uses_second_scratch(uint32_t passes) {
  return passes % 2 == 1 && passes >= 3;
}
// The buffers (of any backend's kind) that `which` names.
template <class Buffers>
const Buffers& pass_target(PassBuffer which, const Buffers& home, const Buffers& a,
                           const Buffers& b) {
  return which == PassBuffer::home ? home : which == PassBuffer::a ? a : b;
}

}  // namespace masav::radix
