#pragma once
// The CPU reference's inner neighbour loops: the candidate test over one contiguous row of
// sorted particles (3 grid cells) on structure-of-arrays copies of the positions, and the
// density sum over a neighbour list. Branch-free, with a fixed summation order (four
// independent lanes); the candidate test has an AVX2 path with the same bits (chosen at run
// time), the density sum is vectorised by the compiler for both targets.
#include <cstdint>

namespace masav::cpu {

// For every k < count with r2 = |p - x_k|^2 < h2 and first + k != self, appends first + k to
// out and r2 to out_r2, in increasing k; returns how many were appended. Both outputs must have
// room for count + 4 entries (the AVX2 path stores four at a time).
uint32_t neighbors_row(const double* xs, const double* ys, const double* zs, uint32_t first,
                       uint32_t count, double px, double py, double pz, double h2, uint32_t self,
                       uint32_t* out, double* out_r2);

// The same without the AVX2 path (what neighbors_row runs where AVX2 is absent; tests compare the
// two), and whether neighbors_row takes the AVX2 path on this CPU.
uint32_t neighbors_row_portable(const double* xs, const double* ys, const double* zs,
                                uint32_t first, uint32_t count, double px, double py, double pz,
                                double h2, uint32_t self, uint32_t* out, double* out_r2);
bool neighbors_row_uses_avx2();

// neighbors_row over the candidates first + b of a row for the set bits b of `bits` only (a
// reach mask, engine/kernels/sph_kernel_params.h), with the same r2 bits; xs, ys, zs start at
// the row's first candidate. Appends at most popcount(bits) entries.
uint32_t neighbors_masked(const double* xs, const double* ys, const double* zs, uint32_t first,
                          uint64_t bits, double px, double py, double pz, double h2, uint32_t self,
                          uint32_t* out, double* out_r2);
// The same in fp32 (the fp32 SPH path's later RK4 stages), r2 as its SIMD row test rounds it.
uint32_t neighbors_masked(const float* xs, const float* ys, const float* zs, uint32_t first,
                          uint64_t bits, float px, float py, float pz, float h2, uint32_t self,
                          uint32_t* out, float* out_r2);

// Sum over k < count of (1 - r2[k] inv_h2)^3, the poly6 terms of sph::density_term for
// neighbours within h.
double density_sum(const double* r2, uint32_t count, double inv_h2);

// out[k] = sph::dfsph_gradient_scale(r2[k]) (-(grad u^2) / r, r = sqrt(r2), u = 1 - r inv_h)
// where r2[k] > 0, else 0: the DFSPH pair gradients' scales, four at a time where AVX2 is
// there (square roots and divisions round alike in every lane: the same bits).
void gradient_scales(const double* r2, uint32_t count, double inv_h, double grad, double* out);

}  // namespace masav::cpu
