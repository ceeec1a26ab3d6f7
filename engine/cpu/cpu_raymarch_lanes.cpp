// Several rays at a time (see cpu_raymarch_lanes.h): the march of cpu_raymarch_lanes_march.inc
// compiled twice, four lanes for any x86-64 (SSE) or other target, and eight for AVX2, chosen when
// the CPU runs. The AVX2 copy is compiled under a target pragma that starts after every include,
// so the header functions it inlines keep their baseline out-of-line copies: nothing that the rest
// of the program may call is compiled for AVX2.
#include "engine/cpu/cpu_raymarch_lanes.h"

#include <vector>

#if defined(__SSE__)
#include <immintrin.h>
#endif

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define MASAV_RAY_LANES_HAVE_AVX2 1
#else
#define MASAV_RAY_LANES_HAVE_AVX2 0
#endif

namespace masav::cpu {

namespace {

namespace lanes4 {
constexpr int kRayLanes = 4;
#if defined(__SSE__)
#define MASAV_RAY_LANES_SSE 1
#else
#define MASAV_RAY_LANES_SSE 0
#endif
#define MASAV_RAY_LANES_AVX2 0
#include "engine/cpu/cpu_raymarch_lanes_march.inc"
#undef MASAV_RAY_LANES_SSE
#undef MASAV_RAY_LANES_AVX2
}  // namespace lanes4

#if MASAV_RAY_LANES_HAVE_AVX2
#pragma GCC push_options
#pragma GCC target("avx2")
namespace lanes8 {
constexpr int kRayLanes = 8;
#define MASAV_RAY_LANES_SSE 0
#define MASAV_RAY_LANES_AVX2 1
#include "engine/cpu/cpu_raymarch_lanes_march.inc"
#undef MASAV_RAY_LANES_SSE
#undef MASAV_RAY_LANES_AVX2
}  // namespace lanes8
#pragma GCC pop_options
#endif

}  // namespace

bool raymarch_lanes_apply(const RaymarchLayout& c) {
  return (c.bits & kRayLerp) == 0u;
}

bool ray_lanes_avx2_available() {
#if MASAV_RAY_LANES_HAVE_AVX2
  static const bool avx2 = __builtin_cpu_supports("avx2");
  return avx2;
#else
  return false;
#endif
}

void pad_volume(const double* volume, UVec3 dims, uint32_t z_begin, uint32_t z_end, float* padded) {
  const size_t px = dims.x + 1u, py = dims.y + 1u;
  for (uint32_t k = z_begin; k < z_end; ++k) {
    const uint32_t ks = hd::min_t(k, dims.z - 1u);
    for (uint32_t j = 0; j < py; ++j) {
      const double* row = volume + (size_t(ks) * dims.y + hd::min_t(j, dims.y - 1u)) * dims.x;
      float* out = padded + (size_t(k) * py + j) * px;
      for (uint32_t i = 0; i < dims.x; ++i) out[i] = float(row[i]);
      out[dims.x] = float(row[dims.x - 1u]);
    }
  }
}

#if MASAV_RAY_LANES_HAVE_AVX2
// Outside the class so that the target attribute applies to this one entry point alone.
__attribute__((target("avx2"))) static void march8(const RaymarchLayout& c, const float* volume,
                                                   const hd::V4<float>* tf,
                                                   const hd::V4<float>* bricks,
                                                   const hd::V4<float>* tf_integral, uint64_t begin,
                                                   uint64_t end, double* image) {
  lanes8::LaneMarch m(c, volume, tf, bricks, tf_integral, image);
  if (c.bits & kRayPreintegrate)
    m.run_preintegrated(begin, end);
  else
    m.run(begin, end);
}
#endif

void raymarch_lanes(const RaymarchLayout& c, const float* volume, const hd::V4<float>* tf,
                    const hd::V4<float>* bricks, const hd::V4<float>* tf_integral, uint64_t begin,
                    uint64_t end, double* image, RayLanes lanes) {
#if MASAV_RAY_LANES_HAVE_AVX2
  if (lanes != RayLanes::four && ray_lanes_avx2_available())
    return march8(c, volume, tf, bricks, tf_integral, begin, end, image);
#endif
  lanes4::LaneMarch m(c, volume, tf, bricks, tf_integral, image);
  if (c.bits & kRayPreintegrate)
    m.run_preintegrated(begin, end);
  else
    m.run(begin, end);
}

}  // namespace masav::cpu
