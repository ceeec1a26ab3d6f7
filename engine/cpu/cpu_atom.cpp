// Electron cloud and nebula lighting on the CPU reference: the shared MASAV_HD bodies
// (engine/atom/*_math.h) in double precision, one particle per loop iteration.
#include <cstring>

#include "engine/atom/atom_checks.h"
#include "engine/kernels/nebula_math.h"
#include "engine/kernels/orbital_math.h"
#include "engine/cpu/cpu_backend.h"

namespace masav::cpu {

void CpuBackend::do_orbital_sample(const OrbitalSampleParams& p, uint64_t, const Buffer<uint32_t>& tables,
                                Buffer<Real4>& positions) {
  const auto* cdf = own(tables.impl(), "orbital_sample").as<uint32_t>();
  auto* out = own(positions.impl(), "orbital_sample").as<double>();
  pool_.parallel_for(p.count, 4096, [&](size_t b, size_t e) {
    for (size_t i = b; i < e; ++i) {
      const hd::V3<double> x = orbital::sample_particle<double>(p, cdf, uint32_t(i));
      out[4 * i] = x.x;
      out[4 * i + 1] = x.y;
      out[4 * i + 2] = x.z;
      out[4 * i + 3] = 0.0;
    }
  });
}

void CpuBackend::do_cloud_density(const CloudDensityParams& p, uint64_t, const Buffer<uint32_t>& cell_start,
                               const Buffer<uint32_t>& cell_end, Buffer<Real>& density) {
  const auto* start = own(cell_start.impl(), "cloud_density").as<uint32_t>();
  const auto* end = own(cell_end.impl(), "cloud_density").as<uint32_t>();
  auto* out = own(density.impl(), "cloud_density").as<double>();
  const double cell = p.grid.cell_size;
  const double scale = 1.0 / (double(p.particles) * cell * cell * cell);
  pool_.parallel_for(grid_cell_count(p.grid), 8192, [&](size_t b, size_t e) {
    for (size_t c = b; c < e; ++c) out[c] = double(end[c] - start[c]) * scale;
  });
}

void CpuBackend::do_nebula_illuminate(const NebulaLightParams& p, uint64_t, const Buffer<Real4>& positions,
                                   const Buffer<Real>& density, Buffer<Real>& illumination) {
  const auto* pos = own(positions.impl(), "nebula_illuminate").as<double>();
  const auto* dens = own(density.impl(), "nebula_illuminate").as<double>();
  auto* out = own(illumination.impl(), "nebula_illuminate").as<double>();
  auto at = [dens](uint32_t id) { return dens[id]; };
  pool_.parallel_for(p.grid.n, 256, [&](size_t b, size_t e) {
    for (size_t i = b; i < e; ++i)
      out[i] = nebula::illumination<double>(p, {pos[4 * i], pos[4 * i + 1], pos[4 * i + 2]}, at);
  });
}

void CpuBackend::do_nebula_view(const NebulaLightParams& p, uint64_t, const Buffer<Real4>& positions,
                             const Buffer<Real>& density, const Buffer<Real>& table,
                             const Buffer<Real>& illumination, Buffer<Real>& light) {
  const auto* pos = own(positions.impl(), "nebula_view").as<double>();
  const auto* dens = own(density.impl(), "nebula_view").as<double>();
  const auto* tab = own(table.impl(), "nebula_view").as<double>();
  const auto* ill = own(illumination.impl(), "nebula_view").as<double>();
  auto* out = own(light.impl(), "nebula_view").as<double>();
  auto dat = [dens](uint32_t id) { return dens[id]; };
  auto tat = [tab](uint32_t k) { return tab[k]; };
  pool_.parallel_for(p.grid.n, 256, [&](size_t b, size_t e) {
    for (size_t i = b; i < e; ++i)
      out[i] = nebula::view_light<double>(p, {pos[4 * i], pos[4 * i + 1], pos[4 * i + 2]}, ill[i],
                                          dat, tat);
  });
}

}  // namespace masav::cpu
