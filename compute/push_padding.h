#pragma once
// Push constants with their padding zeroed. A Vulkan replay compares a captured dispatch's push
// constants byte for byte (compute/vk_stream.h, "Replays"), and parameters that a caller
// brace-initialises leave their padding (MASAV_LAYOUT's alignas(16) tail, engine/core/layout.h)
// unspecified: equal calls would then record anew instead of replaying.
namespace masav::vk {

// Zeroes the bytes of `v` that belong to no member (GCC 11+, Clang 16+; elsewhere a no-op,
// which costs replays, never results).
template <class T>
void clear_padding(T& v) {
#if defined(__has_builtin)
#if __has_builtin(__builtin_clear_padding)
  __builtin_clear_padding(&v);
#endif
#endif
  (void)v;
}

// A copy of `v` with its padding zeroed.
template <class T>
T without_padding(const T& v) {
  T copy = v;
  clear_padding(copy);
  return copy;
}

}  // namespace masav::vk
