// The CPU backend's fp32 SPH path (CpuTuning::sph_precision = fp32, engine/cpu/cpu_sph_simd.h):
// sph_density and sph_forces give the very same bits with every instruction set this CPU runs
// (generic, AVX2, AVX-512) and with 1 or 3 threads, for both pressure models with and without
// walls; and they are not the fp64 reference's bits (the option does change the arithmetic).
// An instruction set this CPU lacks is skipped with a message. Its agreement with the reference
// is the kernel tests' (kernels.cpu.fp32). Runs with --backend=cpu.
#include <doctest/doctest.h>

#include <cstring>
#include <vector>

#include "engine/cpu/cpu_backend.h"
#include "engine/cpu/cpu_sph_simd.h"
#include "engine/sph/sph_kernel_calls.h"
#include "tests/backend_fixture.h"
#include "tests/cpu_fp32_sets.h"
#include "tests/sph_fixture.h"

using namespace masav;

namespace {

// Density, pressure and accelerations as raw doubles.
std::vector<double> density_and_forces(Backend& b, const test::SphCase& c) {
  test::SphBuffers s = test::upload_sph_case(b, c);
  sph_density(b, c.params, {&s.sorted_pos, s.view(), &s.density, &s.pressure, &s.stats});
  sph_forces(b, c.params,
             {&s.sorted_pos, &s.sorted_vel, &s.density, &s.pressure, s.view(), &s.accel, &s.stats});
  std::vector<double> out = b.download(s.density);
  for (double p : b.download(s.pressure)) out.push_back(p);
  for (const Vec4d& a : b.download(s.accel)) out.insert(out.end(), {a.x, a.y, a.z, a.w});
  return out;
}

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

}  // namespace

TEST_CASE("cpu fp32 sph: every instruction set and thread count gives the same bits") {
  if (test::backend().caps().backend != "cpu") return;  // the CPU backend's own code paths
  test::announce_missing_sets();
  test::for_each_model_and_walls(12, 5, [&](test::SphCase& c) {
    cpu::CpuBackend generic(1, cpu::CpuRenderPrecision::fp64, test::fp32_tuning(CpuSphSimd::generic));
    const std::vector<double> want = density_and_forces(generic, c);
    cpu::CpuBackend reference(2);
    CHECK_FALSE(same_bits(want, density_and_forces(reference, c)));
    test::for_each_fp32_backend([&](cpu::CpuBackend& b) {
      CHECK(b.caps().sph_pairs_fp32);
      CHECK(same_bits(density_and_forces(b, c), want));
    });
  });
}

TEST_CASE("cpu fp32 sph: an instruction set this CPU lacks is refused, naming the option") {
  if (test::backend().caps().backend != "cpu") return;
  for (const auto& [name, simd] :
       {std::pair{CpuSphSimd::avx2, cpu::SphSimd::avx2},
        std::pair{CpuSphSimd::avx512, cpu::SphSimd::avx512}}) {
    if (cpu::sph_simd_supported(simd)) continue;
    CHECK_THROWS_WITH_AS(cpu::CpuBackend(1, cpu::CpuRenderPrecision::fp64, test::fp32_tuning(name)),
                         doctest::Contains("cpu.sph_simd"), Error);
  }
  CHECK(cpu::sph_simd_supported(cpu::best_sph_simd()));
}
