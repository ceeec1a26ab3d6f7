#pragma once
// The kernel set. Every backend (Vulkan, CUDA, CPU reference) implements each method; a kernel
// missing from one backend is a build error. Buffers, ordering and timestamps: device_api.h.
#include "engine/device_api.h"
#include "engine/kernel_params.h"
#include "engine/sph/sph_kernel_params.h"

namespace masav {

class Backend : public DeviceApi {
 public:
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
};

}  // namespace masav
