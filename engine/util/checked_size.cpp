#include "engine/util/checked_size.h"

#include <fmt/format.h>

#include <charconv>
#include <string>

#include "engine/core/error.h"

namespace masav {
namespace {

std::string_view trimmed(std::string_view s) {
  const auto blank = [](char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; };
  while (!s.empty() && blank(s.front())) s.remove_prefix(1);
  while (!s.empty() && blank(s.back())) s.remove_suffix(1);
  return s;
}

template <class T>
T parse_whole(std::string_view text, std::string_view where, std::string_view field,
              std::string_view allowed) {
  const std::string_view s = trimmed(text);
  T v{};
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (s.empty() || ec != std::errc() || end != s.data() + s.size())
    throw_invalid(where, field, s.empty() ? "(empty)" : s, allowed);
  return v;
}

}  // namespace

uint64_t checked_add(uint64_t a, uint64_t b, std::string_view where, std::string_view field) {
  uint64_t r = 0;
  if (__builtin_add_overflow(a, b, &r))
    throw_invalid(where, field, fmt::format("{} + {}", a, b), "a size below 2^64");
  return r;
}

uint64_t checked_mul(uint64_t a, uint64_t b, std::string_view where, std::string_view field) {
  uint64_t r = 0;
  if (__builtin_mul_overflow(a, b, &r))
    throw_invalid(where, field, fmt::format("{} x {}", a, b), "a size below 2^64");
  return r;
}

uint64_t parse_u64(std::string_view text, std::string_view where, std::string_view field) {
  return parse_whole<uint64_t>(text, where, field, "a whole number in [0, 2^64 - 1]");
}

int64_t parse_i64(std::string_view text, std::string_view where, std::string_view field) {
  return parse_whole<int64_t>(text, where, field, "a whole number in [-2^63, 2^63 - 1]");
}

uint32_t checked_u32_in(uint64_t v, uint32_t lo, uint32_t hi, std::string_view where,
                        std::string_view field) {
  if (v < lo || v > hi)
    throw_invalid(where, field, fmt::format("{}", v), fmt::format("in [{}, {}]", lo, hi));
  return uint32_t(v);
}

}  // namespace masav
