#pragma once
// The single-precision pair loops of the CPU backend's fp32 SPH path (CpuTuning::sph_precision):
// the candidate test, the density sum and the force pair sum over 16 neighbours at a time. Each
// is built three times, for AVX-512, AVX2 and any x86-64 (or other) CPU, from one body
// (cpu_sph_simd_body.inc) whose every lane does the same IEEE operations in the same order with
// no fused multiply-adds, so the three give the same bits and the choice (best present, or
// CpuTuning::sph_simd) changes the speed only. The bodies take plain arrays and structs defined
// here, never the engine's shared templates: an inline function compiled for AVX-512 in one of
// those files could be the copy the linker keeps for every caller.
#include <cstdint>
#include <string_view>

namespace masav::cpu {

enum class SphSimd : uint8_t { generic, avx2, avx512 };

// The neighbour fields sph_forces reads, 8 floats per particle in this order (one 32-byte row
// each): 16 neighbours' rows are loaded whole and transposed into the 8
// field vectors, which costs less than 8 gathers of 16 lanes.
enum SimdField : uint32_t { kFieldX, kFieldY, kFieldZ, kFieldVx, kFieldVy, kFieldVz, kFieldRho,
                            kFieldPRho2, kFieldCount };
struct SimdPairFields {
  const float* rows;  // particle i's fields at rows[kFieldCount * i + field]
};
// Particle i's own fields.
struct SimdParticle {
  float x, y, z, vx, vy, vz, rho, p_rho2;
};
// The pair terms' constants (SphStepLayout<float>'s, engine/kernels/sph_kernels.h pair_accel).
struct SimdPairConstants {
  float h2, inv_h, inv_h2, pressure, viscosity;
  uint32_t thesis;  // 1: the thesis model's terms (Eqs. 4.5, 4.6), else wcsph's
  uint32_t dfsph;   // 1: no pressure term (the DFSPH solves add it)
};

struct SphSimdKernels {
  SphSimd simd;
  // sph rows: for every k < count with r2 = |p - x_k|^2 < h2 and first + k != self, appends
  // first + k to out and r2 to out_r2 in increasing k; returns how many. Both outputs need room
  // for count + 16 entries (whole vectors are stored).
  uint32_t (*neighbors_row)(const float* xs, const float* ys, const float* zs, uint32_t first,
                            uint32_t count, float px, float py, float pz, float h2, uint32_t self,
                            uint32_t* out, float* out_r2);
  // Sum over k < count of sph::density_term(r2[k]): (1 - r/h)^3 (spiky), or (1 - r2/h^2)^3 for
  // the thesis model (poly6), terms at r >= h zero.
  float (*density_sum)(const float* r2, uint32_t count, const SimdPairConstants& c);
  // Sum over the listed neighbours j (positions xs, ys, zs) of the density terms of their wall
  // images across each set of the walls in `axes` (see pair_sum), as sph::wall_image_density
  // at p: per lane, set by set.
  float (*image_density_sum)(const float* xs, const float* ys, const float* zs,
                             const uint32_t* list, uint32_t count, float px, float py, float pz,
                             uint32_t axes, const float plane[3], const SimdPairConstants& c);
  // Sum over the listed neighbours j of sph::pair_accel(me, o_j) into out[3], for the pairs
  // with r2 < h2, and of their wall images across each set of the walls in `axes` (bit a: a
  // wall within h on axis a, reflecting x_a to 2 plane[a] - x_a; an image moves opposite its
  // particle), as sph::wall_image_accel. Per lane: each neighbour, then its images set by set.
  void (*pair_sum)(const SimdPairFields& f, const SimdParticle& me, const uint32_t* list,
                   uint32_t count, const SimdPairConstants& c, uint32_t axes,
                   const float plane[3], float out[3]);
};

// The kernels for `simd`; throws masav::Error where this CPU lacks it.
const SphSimdKernels& sph_simd_kernels(SphSimd simd);
// The widest this CPU runs.
SphSimd best_sph_simd();
bool sph_simd_supported(SphSimd simd);
std::string_view sph_simd_name(SphSimd simd);

namespace simd_generic {
extern const SphSimdKernels kernels;
}
namespace simd_avx2 {
extern const SphSimdKernels kernels;
}
namespace simd_avx512 {
extern const SphSimdKernels kernels;
}

}  // namespace masav::cpu
