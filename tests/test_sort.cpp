// radix_sort: exact equality with std::stable_sort on the masked key and with the CPU
// reference, for sizes around tile boundaries, adversarial key patterns and every key width.
#include <doctest/doctest.h>
#include <fmt/format.h>

#include <algorithm>
#include <numeric>
#include <random>
#include <vector>

#include "engine/core/error.h"
#include "tests/backend_fixture.h"
#if MASAV_HAVE_VULKAN
#include "compute/vk_backend.h"
#endif

using namespace masav;

namespace {

enum class Pattern { random, all_equal, sorted, reverse, max_keys, few_distinct };

const char* pattern_name(Pattern p) {
  switch (p) {
    case Pattern::random: return "random";
    case Pattern::all_equal: return "all-equal";
    case Pattern::sorted: return "sorted";
    case Pattern::reverse: return "reverse";
    case Pattern::max_keys: return "max-keys";
    case Pattern::few_distinct: return "few-distinct";
  }
  return "?";
}

// Keys carry random garbage above key_bits: the sort must ignore it and keep it.
std::vector<uint32_t> make_keys(size_t n, Pattern pat, uint32_t key_bits, uint64_t seed) {
  std::mt19937_64 rng(seed);
  const uint32_t mask = key_bits == 32 ? ~0u : (1u << key_bits) - 1;
  std::vector<uint32_t> k(n);
  for (size_t i = 0; i < n; ++i) {
    const uint32_t garbage = uint32_t(rng()) & ~mask;
    uint32_t low = 0;
    switch (pat) {
      case Pattern::random: low = uint32_t(rng()); break;
      case Pattern::all_equal: low = 0x5A5A5A5Au; break;
      case Pattern::sorted: low = uint32_t(uint64_t(i) * mask / std::max<size_t>(n, 1)); break;
      case Pattern::reverse: low = uint32_t(uint64_t(n - i) * mask / std::max<size_t>(n, 1)); break;
      case Pattern::max_keys: low = (rng() & 1) ? ~0u : ~0u - 1; break;
      case Pattern::few_distinct: low = uint32_t(rng() % 5) * 0x33333333u; break;
    }
    k[i] = garbage | (low & mask);
  }
  return k;
}

struct Pairs {
  std::vector<uint32_t> keys, values;
};

Pairs expected(const std::vector<uint32_t>& keys, uint32_t key_bits) {
  const uint32_t mask = key_bits == 32 ? ~0u : (1u << key_bits) - 1;
  std::vector<uint32_t> idx(keys.size());
  std::iota(idx.begin(), idx.end(), 0u);
  std::stable_sort(idx.begin(), idx.end(),
                   [&](uint32_t a, uint32_t b) { return (keys[a] & mask) < (keys[b] & mask); });
  Pairs p;
  for (uint32_t i : idx) p.keys.push_back(keys[i]), p.values.push_back(i);
  return p;
}

Pairs sort_on(Backend& b, const std::vector<uint32_t>& keys, uint32_t key_bits, bool with_values,
              SortImpl impl = SortImpl::portable) {
  const size_t n = keys.size();
  auto kb = b.create<uint32_t>(n, "keys");
  auto vb = b.create<uint32_t>(n, "values");
  b.upload(kb, keys);
  std::vector<uint32_t> iota(n);
  std::iota(iota.begin(), iota.end(), 0u);
  b.upload(vb, iota);
  b.radix_sort({uint32_t(n), key_bits, impl}, kb, with_values ? &vb : nullptr);
  return {b.download(kb), with_values ? b.download(vb) : std::vector<uint32_t>{}};
}

}  // namespace

TEST_CASE("radix_sort equals std::stable_sort and the CPU reference") {
  const size_t sizes[] = {0, 1, 2, 3, 7, 255, 256, 257, 2047, 2048, 2049, 4097, 65537, 300001};
  const Pattern patterns[] = {Pattern::random,  Pattern::all_equal, Pattern::sorted,
                              Pattern::reverse, Pattern::max_keys,  Pattern::few_distinct};
  uint64_t seed = 1;
  for (size_t n : sizes)
    for (Pattern pat : patterns)
      for (uint32_t bits : {32u, 17u, 8u, 5u, 1u}) {
        if (n > 4097 && bits != 32 && bits != 17) continue;  // keep the suite fast
        CAPTURE(n);
        CAPTURE(pattern_name(pat));
        CAPTURE(bits);
        const auto keys = make_keys(n, pat, bits, seed++);
        const Pairs want = expected(keys, bits);
        const Pairs got = sort_on(test::backend(), keys, bits, true);
        CHECK(got.keys == want.keys);
        CHECK(got.values == want.values);
        const Pairs ref = sort_on(test::reference(), keys, bits, true);
        CHECK(ref.keys == want.keys);
        CHECK(ref.values == want.values);
      }
}

TEST_CASE("radix_sort sorts keys alone and honours n below the buffer size") {
  Backend& b = test::backend();
  const auto keys = make_keys(5000, Pattern::random, 24, 99);
  const Pairs want = expected(keys, 24);
  CHECK(sort_on(b, keys, 24, false).keys == want.keys);

  // Only the first 1000 of 5000 keys are sorted; the tail stays as it was.
  auto kb = b.create<uint32_t>(keys.size(), "keys");
  b.upload(kb, keys);
  b.radix_sort({1000, 32}, kb, nullptr);
  const auto got = b.download(kb);
  std::vector<uint32_t> head(keys.begin(), keys.begin() + 1000);
  std::stable_sort(head.begin(), head.end());
  CHECK(std::equal(head.begin(), head.end(), got.begin()));
  CHECK(std::equal(keys.begin() + 1000, keys.end(), got.begin() + 1000));
}

TEST_CASE("radix_sort vendor path (CUB on CUDA) equals the portable sort") {
  const auto keys = make_keys(100003, Pattern::random, 32, 7);
  const Pairs want = expected(keys, 32);
  const Pairs got = sort_on(test::backend(), keys, 32, true, SortImpl::vendor);
  CHECK(got.keys == want.keys);
  CHECK(got.values == want.values);
  const auto keys20 = make_keys(70001, Pattern::few_distinct, 20, 8);
  const Pairs want20 = expected(keys20, 20);
  const Pairs got20 = sort_on(test::backend(), keys20, 20, true, SortImpl::vendor);
  CHECK(got20.keys == want20.keys);
  CHECK(got20.values == want20.values);
}

TEST_CASE("radix_sort of 2^25 pairs (the lavapipe binding limit)" * doctest::description("large")) {
  const size_t n = size_t(1) << 25;
  Backend& b = test::backend();
  const auto keys = make_keys(n, Pattern::random, 32, 2025);
  const Pairs got = sort_on(b, keys, 32, true);
  // Linear-time check: keys ascending, equal keys keep ascending indices, values a permutation
  // whose keys are the sorted keys.
  bool ok = true;
  std::vector<uint8_t> seen(n, 0);
  for (size_t i = 0; i < n && ok; ++i) {
    const uint32_t v = got.values[i];
    ok = v < n && !seen[v] && keys[v] == got.keys[i];
    if (ok) seen[v] = 1;
    if (ok && i > 0)
      ok = got.keys[i - 1] < got.keys[i] ||
           (got.keys[i - 1] == got.keys[i] && got.values[i - 1] < v);
    if (!ok) FAIL_CHECK(fmt::format("order broken at {}", i));
  }
  CHECK(ok);
}

TEST_CASE("radix_sort rejects bad parameters with a clear error") {
  Backend& b = test::backend();
  auto kb = b.create<uint32_t>(10, "keys");
  auto vb = b.create<uint32_t>(5, "values");
  CHECK_THROWS_WITH_AS(b.radix_sort({11, 32}, kb, nullptr), doctest::Contains("n = 11"), Error);
  CHECK_THROWS_WITH_AS(b.radix_sort({10, 32}, kb, &vb), doctest::Contains("value buffer"), Error);
  CHECK_THROWS_WITH_AS(b.radix_sort({10, 0}, kb, nullptr), doctest::Contains("key_bits"), Error);
  CHECK_THROWS_WITH_AS(b.radix_sort({10, 33}, kb, nullptr), doctest::Contains("[1, 32]"), Error);
  auto foreign = test::reference().create<uint32_t>(10, "foreign");
  if (&test::reference() != &b)
    CHECK_THROWS_WITH_AS(b.radix_sort({10, 32}, foreign, nullptr),
                         doctest::Contains("another backend"), Error);
}

#if MASAV_HAVE_VULKAN
// The suite "vulkan backend" runs only under --backend=vulkan (test_main.cpp excludes it
// elsewhere and says so).
TEST_SUITE("vulkan backend") {
TEST_CASE("Vulkan scans at a tile of 64: every level of the recursion, then the one-dispatch add") {
  // The default tile (256 x 8) takes the one-dispatch fix-up (scan_add_prefix) up to 4 M
  // entries, beyond what a test sorts; a tile of 64 walks the recursion here: 300,001 keys are
  // 4,688 sort tiles, a digit histogram of 1,200,128 entries, scanned in tiles of 64 (18,752),
  // their totals (293), theirs (5: one dispatch each adding up those before it).
  masav::vk::BackendOptions o;
  o.workgroup_size = 64;
  o.items_per_thread = 1;
  masav::vk::VulkanBackend small(o);
  for (uint32_t bits : {32u, 13u}) {
    CAPTURE(bits);
    const auto keys = make_keys(300001, Pattern::random, bits, 77 + bits);
    const Pairs want = expected(keys, bits);
    const Pairs got = sort_on(small, keys, bits, true);
    CHECK(got.keys == want.keys);
    CHECK(got.values == want.values);
  }
}
}  // TEST_SUITE("vulkan backend")
#endif
