#pragma once
// Helpers of the electron-cloud, nebula and volume kernels that every backend shares: table
// sizes, brick counts, the raymarch camera. Their checks are declared in atom_params.h.
#include "engine/kernels/backend.h"
#include "engine/kernels/volume_math.h"

namespace masav {

size_t orbital_table_size(const OrbitalSampleParams& p);  // uint32 entries the tables need

void check_volume(const VolumeDesc& v, std::string_view kernel);
UVec3 brick_dims(const VolumeDesc& v, uint32_t brick);
// Segments the longest ray through the box takes (what check_raymarch bounds).
uint64_t max_ray_segments(const RaymarchParams& p);

}  // namespace masav
