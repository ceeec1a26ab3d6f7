#pragma once
// The buffers of one SPH kernel case on a backend: host particles uploaded, sorted into the hash
// grid there (positions and velocities reordered into cell order), and the kernels' outputs. The
// cross-check (engine/sph/sph_cross_checks.cpp) and the kernel tests both run kernels on these.
#include <span>
#include <string_view>

#include "engine/grid/hash_grid.h"
#include "engine/kernels/sph_kernel_params.h"
#include "engine/sph/sph_kernel_calls.h"

namespace masav {

struct SphCaseBuffers {
  HashGrid grid;
  Buffer<Real4> pos, vel, sorted_pos, sorted_vel, accel;
  Buffer<Real> density, pressure;
  Buffer<uint32_t> stats;          // zeroed
  Buffer<uint32_t> neighbor_rows;  // room for the neighbour row masks (kSphRowMaskWords n)
  SphGridView view() const { return sph_grid_view(grid); }
};

// p.n particles on p.grid; buffer labels start with `label`.
SphCaseBuffers upload_sph_case(Backend& b, const SphStepParams& p, std::span<const Vec4f> positions,
                               std::span<const Vec4f> velocities, std::string_view label);

}  // namespace masav
