#pragma once
// The CPU reference's inner neighbour loops over one contiguous row of sorted particles
// (3 grid cells), on structure-of-arrays copies of the positions. Four independent lanes per
// loop (a fixed summation order), so the compiler vectorises them without reassociating; built
// for the default target and for AVX2 (chosen at run time).
#include <cstdint>

namespace masav::cpu {

// sum += sum over k < count of (1 - q^2)^3 for q^2 = |p - x_k|^2 inv_h2 < 1; within += those k.
void density_row(const double* xs, const double* ys, const double* zs, uint32_t count, double px,
                 double py, double pz, double inv_h2, double& sum, uint32_t& within);

// Writes first + k to out for every k < count with |p - x_k|^2 < h2 and first + k != self;
// returns how many were written.
uint32_t neighbors_row(const double* xs, const double* ys, const double* zs, uint32_t first,
                       uint32_t count, double px, double py, double pz, double h2, uint32_t self,
                       uint32_t* out);

}  // namespace masav::cpu
