#include "engine/cpu/cpu_sph_rows.h"

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#include <immintrin.h>
#define MASAV_CPU_AVX2_ROWS 1
#endif

namespace masav::cpu {

#if defined(__GNUC__) && defined(__x86_64__) && !defined(__clang__)
#define MASAV_CPU_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define MASAV_CPU_CLONES
#endif

// The portable candidate test: branch-free, one store of each output per candidate.
uint32_t neighbors_row_portable(const double* xs, const double* ys, const double* zs,
                                uint32_t first, uint32_t count, double px, double py, double pz,
                                double h2, uint32_t self, uint32_t* out, double* out_r2) {
  uint32_t n = 0;
  for (uint32_t k = 0; k < count; ++k) {
    const double dx = px - xs[k], dy = py - ys[k], dz = pz - zs[k];
    const double r2 = (dx * dx + dy * dy) + dz * dz;
    const uint32_t j = first + k;
    out[n] = j;
    out_r2[n] = r2;
    n += (r2 < h2) & (j != self) ? 1u : 0u;
  }
  return n;
}

namespace {

// neighbors_masked in T: neighbors_row's r2 order, so the same bits as its test.
template <class T>
uint32_t masked_row(const T* xs, const T* ys, const T* zs, uint32_t first, uint64_t bits, T px,
                    T py, T pz, T h2, uint32_t self, uint32_t* out, T* out_r2) {
  uint32_t n = 0;
  for (; bits != 0; bits &= bits - 1) {
    const uint32_t k = uint32_t(__builtin_ctzll(bits));
    const T dx = px - xs[k], dy = py - ys[k], dz = pz - zs[k];
    const T r2 = (dx * dx + dy * dy) + dz * dz;
    const uint32_t j = first + k;
    out[n] = j;
    out_r2[n] = r2;
    n += (r2 < h2) & (j != self) ? 1u : 0u;
  }
  return n;
}

}  // namespace

uint32_t neighbors_masked(const double* xs, const double* ys, const double* zs, uint32_t first,
                          uint64_t bits, double px, double py, double pz, double h2, uint32_t self,
                          uint32_t* out, double* out_r2) {
  return masked_row(xs, ys, zs, first, bits, px, py, pz, h2, self, out, out_r2);
}
uint32_t neighbors_masked(const float* xs, const float* ys, const float* zs, uint32_t first,
                          uint64_t bits, float px, float py, float pz, float h2, uint32_t self,
                          uint32_t* out, float* out_r2) {
  return masked_row(xs, ys, zs, first, bits, px, py, pz, h2, self, out, out_r2);
}

namespace {

#ifdef MASAV_CPU_AVX2_ROWS
// For each 4-bit mask: the set lanes in increasing order, then the others. As 8 x 32-bit lanes
// (pairs, for 4 doubles) and as 4 x 32-bit lanes (for 4 indices).
struct CompressTable {
  alignas(32) int32_t doubles[16][8];
  alignas(16) int32_t words[16][4];
};
constexpr CompressTable make_compress_table() {
  CompressTable t{};
  for (int m = 0; m < 16; ++m) {
    int order[4] = {0, 0, 0, 0}, n = 0;
    for (int l = 0; l < 4; ++l)
      if (m & (1 << l)) order[n++] = l;
    for (int l = 0; l < 4; ++l)
      if (!(m & (1 << l))) order[n++] = l;
    for (int l = 0; l < 4; ++l) {
      t.words[m][l] = order[l];
      t.doubles[m][2 * l] = 2 * order[l];
      t.doubles[m][2 * l + 1] = 2 * order[l] + 1;
    }
  }
  return t;
}
constexpr CompressTable kCompress = make_compress_table();

// The same test, four candidates at a time: the same operations in the same order (no FMA),
// so the same r2 bits; the neighbours of each four are packed to the front with one permute and
// stored with one vector store per output (which writes up to 3 entries past the last one).
__attribute__((target("avx2"))) uint32_t neighbors_row_avx2(const double* xs, const double* ys,
                                                            const double* zs, uint32_t first,
                                                            uint32_t count, double px, double py,
                                                            double pz, double h2, uint32_t self,
                                                            uint32_t* out, double* out_r2) {
  const __m256d vx = _mm256_set1_pd(px), vy = _mm256_set1_pd(py), vz = _mm256_set1_pd(pz);
  const __m256d vh2 = _mm256_set1_pd(h2);
  const __m128i lanes = _mm_setr_epi32(0, 1, 2, 3);
  uint32_t n = 0, k = 0;
  for (; k + 4 <= count; k += 4) {
    const __m256d dx = _mm256_sub_pd(vx, _mm256_loadu_pd(xs + k));
    const __m256d dy = _mm256_sub_pd(vy, _mm256_loadu_pd(ys + k));
    const __m256d dz = _mm256_sub_pd(vz, _mm256_loadu_pd(zs + k));
    const __m256d r2 = _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(dx, dx), _mm256_mul_pd(dy, dy)),
                                     _mm256_mul_pd(dz, dz));
    unsigned m = unsigned(_mm256_movemask_pd(_mm256_cmp_pd(r2, vh2, _CMP_LT_OQ)));
    const uint32_t j = first + k;
    if (self - j < 4u) m &= ~(1u << (self - j));
    const __m256i pd = _mm256_load_si256(reinterpret_cast<const __m256i*>(kCompress.doubles[m]));
    _mm256_storeu_pd(out_r2 + n,
                     _mm256_castps_pd(_mm256_permutevar8x32_ps(_mm256_castpd_ps(r2), pd)));
    const __m128i pw = _mm_load_si128(reinterpret_cast<const __m128i*>(kCompress.words[m]));
    const __m128i idx = _mm_add_epi32(_mm_set1_epi32(int(j)), lanes);
    _mm_storeu_si128(reinterpret_cast<__m128i*>(out + n),
                     _mm_castps_si128(_mm_permutevar_ps(_mm_castsi128_ps(idx), pw)));
    n += uint32_t(__builtin_popcount(m));
  }
  return n + neighbors_row_portable(xs + k, ys + k, zs + k, first + k, count - k, px, py, pz, h2,
                                    self, out + n, out_r2 + n);
}
#endif

}  // namespace

bool neighbors_row_uses_avx2() {
#ifdef MASAV_CPU_AVX2_ROWS
  static const bool avx2 = __builtin_cpu_supports("avx2");
  return avx2;
#else
  return false;
#endif
}

uint32_t neighbors_row(const double* xs, const double* ys, const double* zs, uint32_t first,
                       uint32_t count, double px, double py, double pz, double h2, uint32_t self,
                       uint32_t* out, double* out_r2) {
#ifdef MASAV_CPU_AVX2_ROWS
  if (neighbors_row_uses_avx2())
    return neighbors_row_avx2(xs, ys, zs, first, count, px, py, pz, h2, self, out, out_r2);
#endif
  return neighbors_row_portable(xs, ys, zs, first, count, px, py, pz, h2, self, out, out_r2);
}

MASAV_CPU_CLONES
double density_sum(const double* r2, uint32_t count, double inv_h2) {
  double s[4] = {0, 0, 0, 0};
  uint32_t k = 0;
  for (; k + 4 <= count; k += 4)
    for (uint32_t l = 0; l < 4; ++l) {
      const double u0 = 1.0 - r2[k + l] * inv_h2;
      const double u = u0 > 0.0 ? u0 : 0.0;  // r2 < h2 yet r2 inv_h2 >= 1 after rounding
      s[l] += u * u * u;
    }
  for (; k < count; ++k) {
    const double u0 = 1.0 - r2[k] * inv_h2;
    const double u = u0 > 0.0 ? u0 : 0.0;
    s[0] += u * u * u;
  }
  return (s[0] + s[1]) + (s[2] + s[3]);
}

MASAV_CPU_CLONES void gradient_scales(const double* r2, uint32_t count, double inv_h, double grad,
                                      double* out) {
  for (uint32_t k = 0; k < count; ++k) {
    const bool positive = r2[k] > 0.0;
    // r2 = 0 (the particle itself) computes with 1, whose result is dropped: no branch, so the
    // loop vectorises, and no division by 0.
    const double r = __builtin_sqrt(positive ? r2[k] : 1.0);
    const double u = 1.0 - r * inv_h;
    const double s = -(grad * u * u) / r;
    out[k] = positive ? s : 0.0;
  }
}

}  // namespace masav::cpu
