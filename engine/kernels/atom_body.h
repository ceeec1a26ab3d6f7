#pragma once
// The electron cloud's per-element bodies: orbital_sample (one particle), cloud_density (one
// cell), nebula_illuminate and nebula_view (one particle), on the math of orbital_math.h and
// nebula_math.h. shaders/orbital_sample.comp, cloud_density.comp and nebula_*.comp are the GLSL
// twins.
#include "engine/kernels/atom_params.h"
#include "engine/kernels/kernel_body.h"
#include "engine/kernels/nebula_math.h"
#include "engine/kernels/orbital_math.h"

namespace masav {

template <>
struct KernelBody<KernelId::orbital_sample> {
  static constexpr uint32_t kCpuGrain = 4096;
  template <class F, class Diag>
  MASAV_HD static void run(uint32_t i, const OrbitalSampleParams& p, Diag&, const uint32_t* tables,
                           hd::V4<F>* positions) {
    const hd::V3<F> x = orbital::sample_particle<F>(p, tables, i);
    positions[i] = hd::V4<F>{x.x, x.y, x.z, F(0)};
  }
};

template <>
struct KernelBody<KernelId::cloud_density> {
  static constexpr uint32_t kCpuGrain = 8192;
  // density[c] = (cell_end[c] - cell_start[c]) / (particles * cell^3).
  template <class F, class Diag>
  MASAV_HD static void run(uint32_t c, const CloudDensityParams& p, Diag&,
                           const uint32_t* cell_start, const uint32_t* cell_end, F* density) {
    const F cell = F(p.grid.cell_size);
    const F scale = F(1) / (F(p.particles) * cell * cell * cell);
    density[c] = F(cell_end[c] - cell_start[c]) * scale;
  }
};

template <>
struct KernelBody<KernelId::nebula_illuminate> {
  static constexpr uint32_t kCpuGrain = 256;
  template <class F, class Diag>
  MASAV_HD static void run(uint32_t i, const NebulaLightParams& p, Diag&,
                           const hd::V4<F>* positions, const F* density, F* illumination) {
    auto at = [density](uint32_t id) { return density[id]; };
    const hd::V4<F> x = positions[i];
    illumination[i] = nebula::illumination<F>(p, hd::V3<F>{x.x, x.y, x.z}, at);
  }
};

template <>
struct KernelBody<KernelId::nebula_view> {
  static constexpr uint32_t kCpuGrain = 256;
  template <class F, class Diag>
  MASAV_HD static void run(uint32_t i, const NebulaLightParams& p, Diag&,
                           const hd::V4<F>* positions, const F* density, const F* table,
                           const F* illumination, F* light) {
    auto dat = [density](uint32_t id) { return density[id]; };
    auto tat = [table](uint32_t k) { return table[k]; };
    const hd::V4<F> x = positions[i];
    light[i] = nebula::view_light<F>(p, hd::V3<F>{x.x, x.y, x.z}, illumination[i], dat, tat);
  }
};

}  // namespace masav
