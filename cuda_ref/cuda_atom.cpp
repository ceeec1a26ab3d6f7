// Electron cloud, nebula lighting, scattering table and volume kernels on CUDA, host side:
// the shared validation, scratch memory, then the launches in atom_kernels.cu,
// scatter_kernels.cu and volume_kernels.cu.
#include "cuda_ref/atom_launch.h"
#include "cuda_ref/cuda_backend.h"
#include "cuda_ref/cuda_check.h"
#include "cuda_ref/cuda_launch.h"
#include "engine/atom/atom_checks.h"
#include "engine/kernels/scatter_math.h"

namespace masav::cuda {
namespace {

template <class T>
T* as(void* p) {
  return static_cast<T*>(p);
}

}  // namespace

void CudaBackend::do_orbital_sample(const OrbitalSampleParams& p, uint64_t, const Buffer<uint32_t>& tables,
                                 Buffer<Real4>& positions) {
  const char* k = "orbital_sample";
  check(launch::orbital_sample(stream_, grid_for_items(p.count, k), p,
                               as<const uint32_t>(ptr(tables.impl(), k)),
                               as<float4>(ptr(positions.impl(), k))),
        k, "launch");
}

void CudaBackend::do_cloud_density(const CloudDensityParams& p, uint64_t, const Buffer<uint32_t>& cell_start,
                                const Buffer<uint32_t>& cell_end, Buffer<Real>& density) {
  const char* k = "cloud_density";
  const uint64_t cells = grid_cell_count(p.grid);
  const double cell = p.grid.cell_size;
  check(launch::cloud_density(stream_, grid_for_items(cells, k),
                              as<const uint32_t>(ptr(cell_start.impl(), k)),
                              as<const uint32_t>(ptr(cell_end.impl(), k)), uint32_t(cells),
                              float(1.0 / (double(p.particles) * cell * cell * cell)),
                              as<float>(ptr(density.impl(), k))),
        k, "launch");
}

void CudaBackend::do_nebula_illuminate(const NebulaLightParams& p, uint64_t, const Buffer<Real4>& positions,
                                    const Buffer<Real>& density, Buffer<Real>& illumination) {
  const char* k = "nebula_illuminate";
  check(launch::nebula_illuminate(stream_, grid_for_items(p.grid.n, k), p,
                                  as<const float4>(ptr(positions.impl(), k)),
                                  as<const float>(ptr(density.impl(), k)),
                                  as<float>(ptr(illumination.impl(), k))),
        k, "launch");
}

void CudaBackend::do_nebula_view(const NebulaLightParams& p, uint64_t, const Buffer<Real4>& positions,
                              const Buffer<Real>& density, const Buffer<Real>& table,
                              const Buffer<Real>& illumination, Buffer<Real>& light) {
  const char* k = "nebula_view";
  check(launch::nebula_view(stream_, grid_for_items(p.grid.n, k), p,
                            as<const float4>(ptr(positions.impl(), k)),
                            as<const float>(ptr(density.impl(), k)),
                            as<const float>(ptr(table.impl(), k)),
                            as<const float>(ptr(illumination.impl(), k)),
                            as<float>(ptr(light.impl(), k))),
        k, "launch");
}

void CudaBackend::do_scatter_table(const ScatterTableParams& p, uint64_t, Buffer<Real>& table,
                                Buffer<uint32_t>& hits) {
  const char* k = "scatter_table";
  const uint32_t entries_per_row = p.bins + kScatterExtras;
  const uint64_t entries = uint64_t(p.rows) * entries_per_row;
  auto* tallies = as<unsigned long long>(scratch_["scatter_table"].reserve(entries * 8, k));
  auto* h = as<uint32_t>(ptr(hits.impl(), k));
  check(cudaMemsetAsync(tallies, 0, entries * 8, stream_), k, "cudaMemsetAsync");
  check(cudaMemsetAsync(h, 0, entries * 4, stream_), k, "cudaMemsetAsync");
  const uint32_t threads = 128;  // photons diverge: small blocks keep the shared tallies busy
  const uint32_t blocks_per_row = (p.photons_per_row + threads - 1) / threads;
  check(launch::scatter_table(stream_, grid_for(uint64_t(p.rows) * blocks_per_row, k), threads, p,
                              blocks_per_row, tallies, h),
        k, "launch");
  check(launch::scatter_finalize(stream_, grid_for((entries + 255) / 256, k), tallies,
                                 uint32_t(entries),
                                 1.0 / (double(1u << scatter::kFixedShift) * p.photons_per_row),
                                 as<float>(ptr(table.impl(), k))),
        k, "launch");
}

void CudaBackend::do_voxelize(const VoxelizeParams& p, uint64_t, const Buffer<Real4>& positions,
                           const Buffer<Real>& light, Buffer<Real>& probability,
                           Buffer<Real>& mean_light, Buffer<Real>& sample) {
  const char* k = "voxelize";
  const uint64_t cells = grid_cell_count(p.grid);
  auto* counts = as<uint32_t>(scratch_["voxelize counts"].reserve((cells + 1) * 4, k));
  auto* sums = as<unsigned long long>(scratch_["voxelize sums"].reserve(cells * 8, k));
  check(cudaMemsetAsync(counts, 0, (cells + 1) * 4, stream_), k, "cudaMemsetAsync");
  check(cudaMemsetAsync(sums, 0, cells * 8, stream_), k, "cudaMemsetAsync");
  check(launch::voxelize_accumulate(stream_, grid_for_items(p.grid.n, k), p,
                                    as<const float4>(ptr(positions.impl(), k)),
                                    as<const float>(ptr(light.impl(), k)), counts, sums),
        k, "launch");
  check(launch::voxelize_finalize(stream_, grid_for_items(cells, k), p, counts, sums,
                                  as<float>(ptr(probability.impl(), k)),
                                  as<float>(ptr(mean_light.impl(), k)),
                                  as<float>(ptr(sample.impl(), k))),
        k, "launch");
}

void CudaBackend::do_volume_bricks(const VolumeBrickParams& p, uint64_t, const Buffer<Real>& volume,
                                const Buffer<Real4>& tf, Buffer<Real4>& bricks) {
  const char* k = "volume_bricks";
  const UVec3 nb = brick_dims(p.volume, p.brick);
  check(launch::volume_bricks(stream_, grid_for_items(uint64_t(nb.x) * nb.y * nb.z, k), p,
                              as<const float>(ptr(volume.impl(), k)),
                              as<const float4>(ptr(tf.impl(), k)),
                              as<float4>(ptr(bricks.impl(), k))),
        k, "launch");
}

void CudaBackend::do_raymarch(const RaymarchParams& p, uint64_t, const Buffer<Real>& volume,
                           const Buffer<Real4>& tf, const Buffer<Real4>& bricks,
                           Buffer<Real4>& image) {
  const char* k = "raymarch";
  check(launch::raymarch(stream_, grid_for_items(uint64_t(p.width) * p.height, k), p,
                         make_ray_camera(p), as<const float>(ptr(volume.impl(), k)),
                         as<const float4>(ptr(tf.impl(), k)),
                         as<const float4>(ptr(bricks.impl(), k)), as<float4>(ptr(image.impl(), k))),
        k, "launch");
}

}  // namespace masav::cuda
