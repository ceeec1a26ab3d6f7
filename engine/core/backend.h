#pragma once
// The kernel set. Every backend (Vulkan, CUDA, CPU reference) implements each method; a kernel
// missing from one backend is a build error. Buffers, ordering and timestamps: device_api.h.
#include "engine/atom/atom_params.h"
#include "engine/core/device_api.h"
#include "engine/core/kernel_params.h"
#include "engine/points/drift_params.h"
#include "engine/sph/sph_kernel_params.h"

namespace masav {

class Backend : public DeviceApi {
 public:
  // ---- demo point cloud (engine/points/) ------------------------------------------------
  // positions[i] for i < p.n: the periodic drift of DriftParams from the uniforms start[4i..]
  // and direction[4i..] (philox_uniform output); .w is the point's speed.
  virtual void drift_points(const DriftParams& p, const Buffer<float>& start,
                            const Buffer<float>& direction, Buffer<Real4>& positions) = 0;

  // ---- random numbers -------------------------------------------------------------------
  // Philox4x32-10 words (see PhiloxParams), out.size() of them.
  virtual void philox_u32(const PhiloxParams& p, Buffer<uint32_t>& out) = 0;
  // The same words as uniform floats in [0, 1): float(word >> 8) * 2^-24, exact everywhere.
  virtual void philox_uniform(const PhiloxParams& p, Buffer<float>& out) = 0;

  // ---- sorting and the hash grid --------------------------------------------------------
  // Stable LSD key-value sort in place; `values` may be null for a key-only sort.
  virtual void radix_sort(const RadixSortParams& p, Buffer<uint32_t>& keys,
                          Buffer<uint32_t>* values) = 0;

  // cells[i] = cell of positions[i], indices[i] = i, for i < g.n (unsorted; sort them next).
  virtual void grid_assign_cells(const GridParams& g, const Buffer<Real4>& positions,
                                 Buffer<uint32_t>& cells, Buffer<uint32_t>& indices) = 0;
  // For sorted cells: [start[c], end[c]) is the range of points in cell c; empty cells 0, 0.
  virtual void grid_cell_ranges(const GridParams& g, const Buffer<uint32_t>& sorted_cells,
                                Buffer<uint32_t>& cell_start, Buffer<uint32_t>& cell_end) = 0;
  // dst[i] = src[order[i]] for i < order.size(); src and dst of the same element kind.
  virtual void gather(const Buffer<uint32_t>& order, const BufferImpl& src, BufferImpl& dst) = 0;
  // counts[i] = points j with |p_j - p_i|^2 <= radius^2 (fp32), searched over the 27 cells
  // around sorted point i. Throws if a point has more candidates than p.max_candidates.
  virtual void grid_count_neighbors(const NeighborParams& p, const Buffer<Real4>& sorted_positions,
                                    const Buffer<uint32_t>& cell_start,
                                    const Buffer<uint32_t>& cell_end,
                                    Buffer<uint32_t>& counts) = 0;

  // ---- SPH fluid (engine/sph/) ----------------------------------------------------------
  // For each sorted particle i < p.n: density (poly6, thesis Eq. 4.4) over the neighbours within
  // p.h found in the 27 cells around cells[i], and pressure from the equation of state.
  // Accumulates candidate counts, overflows (never a silent truncation) into io.stats.
  virtual void sph_density(const SphStepParams& p, const SphDensityIO& io) = 0;
  // Acceleration of each sorted particle: pressure (spiky gradient), viscosity (its laplacian),
  // both per p.model, times the particle's inverse mass (positions' w), plus gravity.
  virtual void sph_forces(const SphStepParams& p, const SphForcesIO& io) = 0;
  // One integrator stage per particle (p.op), then the box walls for ops that end a step;
  // speed, displacement, non-finite values and particles outside the box go to io.stats.
  virtual void sph_integrate(const SphIntegrateParams& p, const SphIntegrateIO& io) = 0;

  // ---- electron cloud, nebula lighting, volume (engine/atom/) ----------------------------
  // positions[i] = (x, y, z, 0) of particle i < p.count, drawn from |psi|^2 by inverting the
  // tables of make_orbital_tables() (engine/atom/orbital_tables.h); particle i uses Philox block
  // i, so every backend draws the same cloud up to fp32 rounding.
  virtual void orbital_sample(const OrbitalSampleParams& p, const Buffer<uint32_t>& tables,
                              Buffer<Real4>& positions) = 0;
  // density[c] = probability per a0^3 of hash-grid cell c (counts from the grid's cell ranges).
  virtual void cloud_density(const CloudDensityParams& p, const Buffer<uint32_t>& cell_start,
                             const Buffer<uint32_t>& cell_end, Buffer<Real>& density) = 0;
  // Monte Carlo scattering table, one photon per invocation: table = rows x (bins +
  // kScatterExtras) weight fractions, hits = photons per entry (exact counts).
  virtual void scatter_table(const ScatterTableParams& p, Buffer<Real>& table,
                             Buffer<uint32_t>& hits) = 0;
  // Eq. 2.4 per particle: light received from the nucleus through the density grid.
  virtual void nebula_illuminate(const NebulaLightParams& p, const Buffer<Real4>& positions,
                                 const Buffer<Real>& density, Buffer<Real>& illumination) = 0;
  // Eq. 2.5-2.6 per particle: scattered toward the viewer and attenuated on the way (the only
  // step a change of viewpoint reruns; a change of Phi only rescales). `table`: rows x bins of
  // make_phase_table() (engine/atom/scatter_cache.h).
  virtual void nebula_view(const NebulaLightParams& p, const Buffer<Real4>& positions,
                           const Buffer<Real>& density, const Buffer<Real>& table,
                           const Buffer<Real>& illumination, Buffer<Real>& light) = 0;
  // Thesis §3.3.2 on the grid's N^3 cells: probability p, mean light g, sample = s g + t p/max p.
  virtual void voxelize(const VoxelizeParams& p, const Buffer<Real4>& positions,
                        const Buffer<Real>& light, Buffer<Real>& probability,
                        Buffer<Real>& mean_light, Buffer<Real>& sample) = 0;
  // Per brick: (value min, value max, largest transfer alpha over that range, 0).
  virtual void volume_bricks(const VolumeBrickParams& p, const Buffer<Real>& volume,
                             const Buffer<Real4>& tf, Buffer<Real4>& bricks) = 0;
  // image[y * width + x] = RGBA (colour premultiplied by alpha) of pixel (x, y), y = 0 on top.
  virtual void raymarch(const RaymarchParams& p, const Buffer<Real>& volume,
                        const Buffer<Real4>& tf, const Buffer<Real4>& bricks,
                        Buffer<Real4>& image) = 0;
};

}  // namespace masav
