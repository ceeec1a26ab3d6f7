#pragma once
// The CPU backend's fp32 path for the tests that compare its instruction sets
// (test_cpu_sph_simd.cpp, test_cpu_dfsph_terms.cpp): its tuning, and every instruction set by
// option and kind, those this CPU lacks announced as skipped.
#include <doctest/doctest.h>

#include <utility>

#include "engine/core/tuning.h"
#include "engine/cpu/cpu_backend.h"
#include "engine/cpu/cpu_sph_simd.h"

namespace masav::test {

inline Tuning fp32_tuning(CpuSphSimd simd) {
  Tuning t;
  t.cpu.sph_precision = CpuSphPrecision::fp32;
  t.cpu.sph_simd = simd;
  return t;
}

inline constexpr std::pair<CpuSphSimd, cpu::SphSimd> kFp32Sets[] = {
    {CpuSphSimd::generic, cpu::SphSimd::generic},
    {CpuSphSimd::avx2, cpu::SphSimd::avx2},
    {CpuSphSimd::avx512, cpu::SphSimd::avx512}};

// Calls f(b) with a CPU backend b of the fp32 path for every instruction set this CPU runs, with
// 1 and 3 threads (each captured for the checks in f).
template <class F>
void for_each_fp32_backend(F&& f) {
  for (const auto& [name, simd] : kFp32Sets) {
    if (!cpu::sph_simd_supported(simd)) continue;
    for (unsigned threads : {1u, 3u}) {
      CAPTURE(cpu::sph_simd_name(simd));
      CAPTURE(threads);
      cpu::CpuBackend b(threads, cpu::CpuRenderPrecision::fp64, fp32_tuning(name));
      f(b);
    }
  }
}

inline void announce_missing_sets() {
  for (const auto& [name, simd] : kFp32Sets)
    if (!cpu::sph_simd_supported(simd))
      MESSAGE("skipped: this CPU lacks " << cpu::sph_simd_name(simd));
}

}  // namespace masav::test
