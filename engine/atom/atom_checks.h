#pragma once
// Validation of the electron-cloud, nebula and volume kernels, shared by every backend so that
// each rejects the same inputs with the same message (field, value, allowed range).
#include "engine/kernels/volume_math.h"
#include "engine/core/backend.h"

namespace masav {

void check_orbital_sample(const DeviceApi& dev, const OrbitalSampleParams& p,
                          const Buffer<uint32_t>& tables, const Buffer<Real4>& positions);
size_t orbital_table_size(const OrbitalSampleParams& p);  // uint32 entries the tables need

void check_cloud_density(const DeviceApi& dev, const CloudDensityParams& p,
                         const Buffer<uint32_t>& start, const Buffer<uint32_t>& end,
                         const Buffer<Real>& density);

void check_scatter_table(const DeviceApi& dev, const ScatterTableParams& p,
                         const Buffer<Real>& table, const Buffer<uint32_t>& hits);

// `out`: the per-particle output (illumination or light).
void check_nebula(const DeviceApi& dev, const NebulaLightParams& p, const Buffer<Real4>& positions,
                  const Buffer<Real>& density, const Buffer<Real>& out, std::string_view kernel);
void check_nebula_view(const DeviceApi& dev, const NebulaLightParams& p, const Buffer<Real>& table,
                       const Buffer<Real>& illumination);

void check_voxelize(const DeviceApi& dev, const VoxelizeParams& p, const Buffer<Real4>& positions,
                    const Buffer<Real>& light, const Buffer<Real>& probability,
                    const Buffer<Real>& mean_light, const Buffer<Real>& sample);

void check_volume(const VolumeDesc& v, std::string_view kernel);
void check_volume_bricks(const DeviceApi& dev, const VolumeBrickParams& p,
                         const Buffer<Real>& volume, const Buffer<Real4>& tf,
                         const Buffer<Real4>& bricks);
void check_raymarch(const DeviceApi& dev, const RaymarchParams& p, const Buffer<Real>& volume,
                    const Buffer<Real4>& tf, const Buffer<Real4>& bricks,
                    const Buffer<Real4>& image);

UVec3 brick_dims(const VolumeDesc& v, uint32_t brick);
// The camera and derived constants every backend's raymarch uses (fp32, computed once).
volume::RayCamera make_ray_camera(const RaymarchParams& p);
// Segments the longest ray through the box takes (what check_raymarch bounds).
uint64_t max_ray_segments(const RaymarchParams& p);

}  // namespace masav
