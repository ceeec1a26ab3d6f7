#pragma once
// A kernel's loop-limit case: lavapipe silently stops a shader invocation after 65,535 loop
// iterations (PLATFORM.md), so every kernel of kernels.inc is driven at its worst case on a
// backend that counts loop iterations (test::loop_counter) and the largest count must stay below
// Capabilities::max_loop_iterations. A case sits next to its kernel's test and names the kernels
// it drives:
//
//   LOOP_LIMIT_CASE("gather loops once per element", KernelId::gather) {
//     Backend& b = test::loop_counter();
//     ... run the kernel at its worst case ...
//     CHECK(test::ticks_of(b) <= 1);
//   }
//
// tests/test_loop_limit.cpp fails when a kernel has no case.
#include <doctest/doctest.h>

#include <initializer_list>
#include <optional>
#include <set>

#include "engine/core/pp.h"
#include "engine/kernels/backend.h"

namespace masav::test {

// The kernels that have a loop-limit case.
inline std::set<KernelId>& loop_limit_covered() {
  static std::set<KernelId> kernels;
  return kernels;
}
struct LoopLimitCovers {
  LoopLimitCovers(std::initializer_list<KernelId> kernels) { loop_limit_covered().insert(kernels); }
};

// The most loop iterations any invocation ran since the last call.
inline uint32_t ticks_of(Backend& b) {
  const std::optional<uint32_t> t = b.take_max_loop_ticks();
  REQUIRE(t.has_value());
  return *t;
}

}  // namespace masav::test

#define LOOP_LIMIT_CASE(name, ...)                                                 \
  static const ::masav::test::LoopLimitCovers MASAV_PP_CAT(loop_limit_covers_,     \
                                                           __LINE__){__VA_ARGS__}; \
  TEST_CASE(name* doctest::test_suite("loop limit"))
