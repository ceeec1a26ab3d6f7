#pragma once
// The kernel set. Every backend (Vulkan, CUDA, CPU reference) implements each method; a kernel
// missing from one backend is a build error. Buffers, ordering and timestamps: device_api.h.
#include "engine/device_api.h"
#include "engine/kernel_params.h"
#include "engine/points/drift_params.h"

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

  // ---- electron cloud, nebula lighting, volume (engine/atom/) ----------------------------
};

}  // namespace masav
