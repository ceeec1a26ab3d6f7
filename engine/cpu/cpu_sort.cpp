// Stable LSD radix sort for the CPU reference: per pass, every chunk counts its digits, a
// digit-major prefix over (digit, chunk) gives each chunk's output offsets, and each chunk then
// scatters its keys in order -- the same reduce-then-scan structure as the GPU sorts.
#include <array>
#include <cstring>
#include <vector>

#include "engine/cpu/cpu_backend.h"
#include "engine/kernels/radix.h"

namespace masav::cpu {

void radix_sort_host(ThreadPool& pool, uint32_t n, uint32_t key_bits, uint32_t* keys,
                     uint32_t* values) {
  if (n <= 1) return;
  const uint32_t passes = radix::pass_count(key_bits);
  std::vector<uint32_t> tmp_keys(n), tmp_vals(values ? n : 0);
  uint32_t *ks = keys, *kd = tmp_keys.data();
  uint32_t *vs = values, *vd = values ? tmp_vals.data() : nullptr;

  const size_t chunks = std::min<size_t>(pool.size() * 2, std::max<size_t>(1, n / 65536));
  std::vector<std::array<uint32_t, radix::kRadix>> counts(chunks);

  for (uint32_t pass = 0; pass < passes; ++pass) {
    const uint32_t shift = pass * radix::kDigitBits, bits = radix::pass_bits(key_bits, pass);
    const uint32_t radix_size = 1u << bits;
    pool.run_chunks(n, chunks, [&](size_t c, size_t b, size_t e) {
      auto& h = counts[c];
      h.fill(0);
      for (size_t i = b; i < e; ++i) ++h[radix::digit(ks[i], shift, bits)];
    });
    uint32_t running = 0;  // digit-major exclusive prefix: all of digit d before digit d+1
    for (uint32_t d = 0; d < radix_size; ++d)
      for (size_t c = 0; c < chunks; ++c) {
        const uint32_t cnt = counts[c][d];
        counts[c][d] = running;
        running += cnt;
      }
    pool.run_chunks(n, chunks, [&](size_t c, size_t b, size_t e) {
      auto& off = counts[c];
      for (size_t i = b; i < e; ++i) {
        const uint32_t dst = off[radix::digit(ks[i], shift, bits)]++;
        kd[dst] = ks[i];
        if (vs) vd[dst] = vs[i];
      }
    });
    std::swap(ks, kd);
    std::swap(vs, vd);
  }
  if (ks != keys) {  // odd pass count: the result sits in the scratch arrays
    std::memcpy(keys, ks, size_t(n) * 4);
    if (values) std::memcpy(values, vs, size_t(n) * 4);
  }
}

}  // namespace masav::cpu
