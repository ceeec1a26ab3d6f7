// The CPU backend's fp32 raymarch, several rays at a time. One ray's samples form a chain of
// dependent operations (position, trilinear gather, transfer lookup, opacity, compositing) about
// a hundred cycles long, of which an out-of-order core overlaps little; marching 4 or 8 rays side
// by side gives it independent chains and lets the arithmetic run as SIMD across rays.
// Each lane takes the samples of volume::raymarch_pixel's march (or the pre-integrated one) whose
// value could be visible, with the same operations in the same order and the same termination, so
// the image is that march's bit for bit; it looks its brick up at every sample instead of once per
// cube of occupied bricks, and may take a transparent sample more after a skip (it composites
// exactly 0). A lane takes the next pixel as soon as its ray ends, so lanes stay busy whatever
// their rays' lengths.
#ifndef MASAV_ENGINE_CPU_CPU_RAYMARCH_LANES_H
#define MASAV_ENGINE_CPU_CPU_RAYMARCH_LANES_H

#include <cstdint>

#include "engine/kernels/atom_params.h"
#include "engine/kernels/volume_math.h"

namespace masav::cpu {

// Whether raymarch_lanes renders layout c: front-to-back compositing, sampled at segment
// midpoints or pre-integrated (not lerp); shading and clipping included.
bool raymarch_lanes_apply(const RaymarchLayout& c);

// The volume in fp32 with one more voxel on each axis, a copy of the last (padded[(k * (dims.y + 1)
// + j) * (dims.x + 1) + i] = volume[min(k, dims.z - 1)][min(j, ...)][min(i, ...)]), for the
// slices z_begin <= k < z_end of dims.z + 1: what raymarch_lanes reads.
void pad_volume(const double* volume, UVec3 dims, uint32_t z_begin, uint32_t z_end, float* padded);

// Lanes per vector: eight where the CPU has AVX2 (best), else four; `four` forces four.
enum class RayLanes { best, four };
bool ray_lanes_avx2_available();

// Marches invocations [begin, end) of volume::tile_pixel's order and writes each pixel's RGBA to
// image[4 * (y * width + x) ...] (padding invocations write nothing). volume from pad_volume; tf,
// bricks and tf_integral (read where c is pre-integrated) as the raymarch kernel reads them, in
// fp32.
void raymarch_lanes(const RaymarchLayout& c, const float* volume, const hd::V4<float>* tf,
                    const hd::V4<float>* bricks, const hd::V4<float>* tf_integral, uint64_t begin,
                    uint64_t end, double* image, RayLanes lanes = RayLanes::best);

}  // namespace masav::cpu

#endif
