// Electron cloud and nebula lighting on Vulkan: shared validation, then the GLSL kernels
// (shaders/orbital_sample.comp, cloud_density.comp, nebula_*.comp).
#include <bit>
#include <cstring>

#include "compute/vk_backend.h"
#include "engine/atom/atom_checks.h"
#include "engine/core/error.h"

namespace masav::vk {
namespace {

struct OrbitalPush {
  uint32_t count, placement, seed[2];
  uint32_t radial_bins, polar_bins, azimuth_bins, azimuth_periods;
  float radial_max, azimuth_offset;
};
struct DensityPush {
  uint32_t cells;
  float scale;
};
struct NebulaPush {
  float origin_inv_cell[4];
  uint32_t dims_n[4];
  float nucleus_cell[4];
  float viewer_kappa[4];
  float power_albedo_core_step[4];
  uint32_t path_rows_bins[4];
};
static_assert(sizeof(NebulaPush) == 96);

uint64_t groups_for(uint64_t items, uint32_t wg) { return (items + wg - 1) / wg; }

NebulaPush nebula_push(const NebulaLightParams& p) {
  const GridParams& g = p.grid;
  return NebulaPush{{g.origin.x, g.origin.y, g.origin.z, g.inv_cell},
                    {g.dims.x, g.dims.y, g.dims.z, g.n},
                    {p.nucleus.x, p.nucleus.y, p.nucleus.z, g.cell_size},
                    {p.viewer.x, p.viewer.y, p.viewer.z, p.kappa_a2},
                    {p.source_power_lm, p.albedo, p.core_radius_a0, p.step_a0},
                    {uint32_t(p.path), p.table_rows, p.table_bins,
                     std::bit_cast<uint32_t>(p.table_tau_step)}};
}

}  // namespace

void VulkanBackend::do_orbital_sample(const OrbitalSampleParams& p, uint64_t, const Buffer<uint32_t>& tables,
                                   Buffer<Real4>& positions) {
  const OrbitalPush push{p.count,
                         uint32_t(p.placement),
                         {uint32_t(p.seed), uint32_t(p.seed >> 32)},
                         p.radial_bins,
                         p.polar_bins,
                         p.azimuth_bins,
                         p.azimuth_periods,
                         p.radial_max_a0,
                         p.azimuth_offset};
  run({"orbital_sample", 2, sizeof push, {}},
      {alloc(tables.impl(), "orbital_sample"), alloc(positions.impl(), "orbital_sample")}, &push,
      groups_for(p.count, options_.workgroup_size));
}

void VulkanBackend::do_cloud_density(const CloudDensityParams& p, uint64_t, const Buffer<uint32_t>& cell_start,
                                  const Buffer<uint32_t>& cell_end, Buffer<Real>& density) {
  const uint64_t cells = grid_cell_count(p.grid);
  const double cell = p.grid.cell_size;
  const DensityPush push{uint32_t(cells), float(1.0 / (double(p.particles) * cell * cell * cell))};
  run({"cloud_density", 3, sizeof push, {}},
      {alloc(cell_start.impl(), "cloud_density"), alloc(cell_end.impl(), "cloud_density"),
       alloc(density.impl(), "cloud_density")},
      &push, groups_for(cells, options_.workgroup_size));
}

void VulkanBackend::do_nebula_illuminate(const NebulaLightParams& p, uint64_t, const Buffer<Real4>& positions,
                                      const Buffer<Real>& density, Buffer<Real>& illumination) {
  const char* k = "nebula_illuminate";
  const NebulaPush push = nebula_push(p);
  run({k, 3, sizeof push, {}},
      {alloc(positions.impl(), k), alloc(density.impl(), k), alloc(illumination.impl(), k)}, &push,
      groups_for(p.grid.n, options_.workgroup_size));
}

void VulkanBackend::do_nebula_view(const NebulaLightParams& p, uint64_t, const Buffer<Real4>& positions,
                                const Buffer<Real>& density, const Buffer<Real>& table,
                                const Buffer<Real>& illumination, Buffer<Real>& light) {
  const char* k = "nebula_view";
  const NebulaPush push = nebula_push(p);
  run({k, 5, sizeof push, {}},
      {alloc(positions.impl(), k), alloc(density.impl(), k), alloc(table.impl(), k),
       alloc(illumination.impl(), k), alloc(light.impl(), k)},
      &push, groups_for(p.grid.n, options_.workgroup_size));
}

}  // namespace masav::vk
