#pragma once
// The names of a small enum's values, numbered 0 .. N-1 in declaration order: one table gives
// both directions (for messages, scene files and flags).
#include <cstddef>
#include <optional>
#include <string_view>

namespace masav {

template <class E, size_t N>
const char* enum_name(E value, const char* const (&names)[N]) {
  const size_t i = size_t(value);
  return i < N ? names[i] : "?";
}

template <class E, size_t N>
std::optional<E> enum_from_name(std::string_view name, const char* const (&names)[N]) {
  for (size_t i = 0; i < N; ++i)
    if (name == names[i]) return E(i);
  return std::nullopt;
}

}  // namespace masav
