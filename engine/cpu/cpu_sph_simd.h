#pragma once
// The single-precision pair loops of the CPU backend's fp32 SPH path (CpuTuning::sph_precision):
// the candidate test, the density sum and the force pair sum over 16 neighbours at a time, and
// the DFSPH solves' sums over 16 kept terms at a time. Each
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

// A particle's DFSPH terms on the fp32 path (DfsphTerms32, engine/cpu/cpu_dfsph_terms.h): term
// k's gradient m grad W (gx, gy, gz)[k] and its neighbour js[k] = j | mirror set << 29 (the
// set's bit a: the image reflected across axis a; 0: the pair). Each array can be read 16
// entries past `count` (values unused).
struct SimdDfsphTerms {
  const float *gx, *gy, *gz;
  const uint32_t* js;
  uint32_t count;
};

// Where dfsph_pair_terms writes a particle's terms (DfsphTerms32's arrays at its next entry).
struct SimdDfsphOut {
  float *gx, *gy, *gz;
  uint32_t* js;
};
// The spiky gradient's constants (DfsphLayout<float>'s).
struct SimdDfsphConstants {
  float inv_h, grad;
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
  // DFSPH's density change rate (sph::dfsph_rate_of's sum): over the terms, g_k . (v_i - v_j'),
  // v_j' neighbour j's velocity (vel[4 j + a], a = 0, 1, 2) with the set's components negated
  // (sph::mirror_velocity); the particle's own images read its own row.
  float (*dfsph_divergence)(const SimdDfsphTerms& t, float vx, float vy, float vz,
                            const float* vel);
  // The pair terms of the particle at p with its `count` listed neighbours (each within h;
  // positions in fp32 rows of 4, x y z at xyz[4 j]):
  // out.gx/gy/gz[k] = m grad_i W(p - x_j) of list[k] (sph::dfsph_gradient, 0 at r = 0),
  // out.js[k] = list[k]; and their sum into sum[3] and the sum of their squares into *sum2
  // (dfsph_factor_of's sums). Writes up to 16 entries past count.
  void (*dfsph_pair_terms)(const float* xyz, const uint32_t* list, uint32_t count, float px,
                           float py, float pz, const SimdDfsphConstants& c,
                           const SimdDfsphOut& out, float sum[3], float* sum2);
  // The wall images of those neighbours within h (sets within `axes`, bit a: reflected across
  // the plane x_a = plane[a]; as sph::for_each_wall_image_set), 16 neighbours at a time, set by
  // set within
  // a block of 16 neighbours: their terms at `out` (js = j | set << 29), their sum and squares
  // added to sum[3] and *sum2. Returns how many; writes up to 16 entries past them.
  uint32_t (*dfsph_image_terms)(const float* xyz, const uint32_t* list, uint32_t count,
                                float px, float py, float pz, uint32_t axes, const float plane[3],
                                float h2, const SimdDfsphConstants& c, const SimdDfsphOut& out,
                                float sum[3], float* sum2);
  // dfsph_correction_of's sum over the terms of (kappa_i + kappa[j]) g_k, into out[3].
  void (*dfsph_kappa_gradient)(const SimdDfsphTerms& t, float kappa_i, const float* kappa,
                               float out[3]);
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
