#include "engine/cpu/cpu_sph_simd.h"

#include <fmt/format.h>

#include "engine/core/error.h"

namespace masav::cpu {

bool sph_simd_supported(SphSimd simd) {
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
  switch (simd) {
    case SphSimd::avx512:
      return __builtin_cpu_supports("avx512f");
    case SphSimd::avx2:
      return __builtin_cpu_supports("avx2");
    case SphSimd::generic:
      return true;
  }
  return false;
#else
  return simd == SphSimd::generic;
#endif
}

SphSimd best_sph_simd() {
  for (SphSimd s : {SphSimd::avx512, SphSimd::avx2})
    if (sph_simd_supported(s)) return s;
  return SphSimd::generic;
}

std::string_view sph_simd_name(SphSimd simd) {
  switch (simd) {
    case SphSimd::avx512:
      return "avx512";
    case SphSimd::avx2:
      return "avx2";
    case SphSimd::generic:
      break;
  }
  return "generic";
}

const SphSimdKernels& sph_simd_kernels(SphSimd simd) {
  if (!sph_simd_supported(simd))
    throw Error("cpu", "--tune", fmt::format("invalid cpu.sph_simd = {}", sph_simd_name(simd)),
                fmt::format("this CPU runs at most {}", sph_simd_name(best_sph_simd())));
  switch (simd) {
    case SphSimd::avx512:
      return simd_avx512::kernels;
    case SphSimd::avx2:
      return simd_avx2::kernels;
    case SphSimd::generic:
      break;
  }
  return simd_generic::kernels;
}

}  // namespace masav::cpu
