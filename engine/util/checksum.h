#pragma once
// FNV-1a, 64 bits: the checksum of cache payloads and the hash that names cache files. Not
// cryptographic: it catches damage (overwritten bytes, flipped bits, truncation), not forgery.
#include <cstddef>
#include <cstdint>
#include <string_view>

namespace masav {

inline constexpr uint64_t kFnv1a64Offset = 0xcbf29ce484222325ull;

// Continues a running hash `h` over n more bytes (start from kFnv1a64Offset).
inline uint64_t fnv1a64(const void* data, size_t n, uint64_t h = kFnv1a64Offset) {
  const auto* p = static_cast<const unsigned char*>(data);
  for (size_t i = 0; i < n; ++i) h = (h ^ p[i]) * 0x100000001b3ull;
  return h;
}

inline uint64_t fnv1a64(std::string_view s, uint64_t h = kFnv1a64Offset) {
  return fnv1a64(s.data(), s.size(), h);
}

}  // namespace masav
