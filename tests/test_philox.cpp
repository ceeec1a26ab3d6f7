// Philox4x32-10 streams: the Random123 known answers through the kernel, carries across the
// 32-bit block counter, and bit-identical words and floats against the CPU reference.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <vector>

#include "engine/kernels/philox.h"
#include "tests/backend_fixture.h"

using namespace masav;

namespace {

struct Kat {
  std::array<uint32_t, 4> ctr;
  std::array<uint32_t, 2> key;
  std::array<uint32_t, 4> out;
};
// Random123 kat_vectors, philox4x32 10 (counter, key -> output).
const Kat kKats[] = {
    {{0, 0, 0, 0}, {0, 0}, {0x6627e8d5, 0xe169c58d, 0xbc57ac4c, 0x9b00dbd8}},
    {{0xffffffff, 0xffffffff, 0xffffffff, 0xffffffff},
     {0xffffffff, 0xffffffff},
     {0x408f276d, 0x41c83b0e, 0xa20bc7c6, 0x6d5451fd}},
    {{0x243f6a88, 0x85a308d3, 0x13198a2e, 0x03707344},
     {0xa4093822, 0x299f31d0},
     {0xd16cfe09, 0x94fdcceb, 0x5001e420, 0x24126ea1}},
};

uint64_t pack(uint32_t lo, uint32_t hi) { return uint64_t(hi) << 32 | lo; }

}  // namespace

TEST_CASE("philox_u32 reproduces the Random123 known answers") {
  Backend& b = test::backend();
  for (const Kat& k : kKats) {
    // Counter (block lo, block hi, stream lo, stream hi), key (seed lo, seed hi).
    PhiloxParams p{pack(k.key[0], k.key[1]), pack(k.ctr[2], k.ctr[3]), pack(k.ctr[0], k.ctr[1])};
    auto out = b.create<uint32_t>(4, "kat");
    b.philox_u32(p, out);
    const auto got = b.download(out);
    for (int j = 0; j < 4; ++j) CHECK(got[j] == k.out[j]);
  }
}

TEST_CASE("philox_u32 matches the CPU reference bit for bit, carries included") {
  Backend& b = test::backend();
  Backend& r = test::reference();
  struct Case {
    PhiloxParams p;
    size_t n;
  };
  const Case cases[] = {
      {{0, 0, 0}, 0},
      {{1, 2, 3}, 1},
      {{1, 2, 3}, 7},                               // partial last block
      {{42, 7, 0xFFFFFFFEull}, 64},                 // block counter carries into its high word
      {{0xDEADBEEFCAFEF00Dull, 0x0123456789ull, 1ull << 40}, 1000003},
  };
  for (const auto& c : cases) {
    CAPTURE(c.n);
    auto ob = b.create<uint32_t>(c.n, "words");
    auto orf = r.create<uint32_t>(c.n, "words");
    b.philox_u32(c.p, ob);
    r.philox_u32(c.p, orf);
    const auto got = b.download(ob), want = r.download(orf);
    REQUIRE(got.size() == want.size());
    CHECK(std::memcmp(got.data(), want.data(), got.size() * 4) == 0);
    for (size_t i = 0; i < std::min<size_t>(c.n, 64); ++i) {  // against the shared header too
      const auto blk = philox::stream_block(c.p.seed, c.p.stream, c.p.first_block + i / 4);
      CHECK(got[i] == blk.w[i % 4]);
    }
  }
}

TEST_CASE("philox streams with different ids or seeds differ") {
  Backend& b = test::backend();
  auto a = b.create<uint32_t>(4096, "a");
  auto c = b.create<uint32_t>(4096, "c");
  auto d = b.create<uint32_t>(4096, "d");
  b.philox_u32({7, 0, 0}, a);
  b.philox_u32({7, 1, 0}, c);
  b.philox_u32({8, 0, 0}, d);
  const auto va = b.download(a), vc = b.download(c), vd = b.download(d);
  size_t same_c = 0, same_d = 0;
  for (size_t i = 0; i < va.size(); ++i) same_c += va[i] == vc[i], same_d += va[i] == vd[i];
  CHECK(same_c < 4);  // 4096 draws: a few equal words by chance at most
  CHECK(same_d < 4);
}

TEST_CASE("philox_uniform gives identical floats in [0, 1) with the right mean") {
  Backend& b = test::backend();
  Backend& r = test::reference();
  const size_t n = 1 << 20;
  const PhiloxParams p{2024, 3, 0};
  auto ub = b.create<float>(n, "u");
  auto ur = r.create<float>(n, "u");
  b.philox_uniform(p, ub);
  r.philox_uniform(p, ur);
  const auto got = b.download(ub), want = r.download(ur);
  CHECK(std::memcmp(got.data(), want.data(), n * 4) == 0);
  double sum = 0;
  float lo = 1, hi = 0;
  for (float u : got) sum += u, lo = std::min(lo, u), hi = std::max(hi, u);
  CHECK(lo >= 0.0f);
  CHECK(hi < 1.0f);
  // Mean of n uniforms: standard deviation sqrt(1/12/n) = 2.8e-4; allow 5 sigma.
  CHECK(std::abs(sum / n - 0.5) < 5 * std::sqrt(1.0 / 12.0 / n));
}
