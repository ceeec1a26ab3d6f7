// Parameters of the hash-grid kernels (thesis §4.2.2): grid_assign_cells, grid_cell_ranges,
// gather, grid_count_neighbors, and the passes of the counting sort by cell (grid_count_cells or
// grid_assign_count, grid_cell_offsets, grid_scatter_cells, grid_rank_in_cell). Shared by C++, CUDA
// and GLSL (engine/core/layout.h).
#ifndef MASAV_KERNELS_GRID_PARAMS_H
#define MASAV_KERNELS_GRID_PARAMS_H
#include "engine/core/layout.h"

MASAV_NAMESPACE_BEGIN

// Uniform grid over a box (thesis Eq. 4.1-4.2). A point's cell is floor((p - origin) * inv_cell)
// per axis in fp32, clamped to [0, dims-1]; cell id = (cx * dims.y + cy) * dims.z + cz.
MASAV_LAYOUT(GridParams) {
  vec3 origin;
  float cell_size MASAV_INIT(1.0f);
  uvec3 dims MASAV_INIT(uvec3(1, 1, 1));
  uint n MASAV_INIT(0u);            // points
  float inv_cell MASAV_INIT(1.0f);  // fp32 1/cell_size computed once on the host (make_grid_params)
};

// Neighbours of each sorted point within `radius` over the 27 cells around it (itself included).
MASAV_LAYOUT(NeighborParams) {
  GridParams grid;
  float radius MASAV_INIT(1.0f);
  float radius2 MASAV_INIT(1.0f);  // fp32 radius*radius computed on the host
  // Candidates examined per point at most; beyond it the kernel reports an overflow rather than
  // run longer than the device's loop limit (Capabilities::max_loop_iterations).
  uint max_candidates MASAV_INIT(60000u);
};

// What gather reads: dst[i] = src[order[i]] for i < n; an index of src_count or more is reported.
MASAV_LAYOUT(GatherLayout) {
  uint n;
  uint src_count;
};

// The first pass of a counting sort by cell: counts[c] += the number of i < n with cells[i] == c,
// for c < cell_count. It adds, so one table can count several particle sets; fill it with 0
// first for one set's counts. A cell id of cell_count or more is reported.
MASAV_LAYOUT(CellCountParams) {
  uint n;
  uint cell_count;
};

// The first pass fused with the assignment: cells[i] = the cell of positions[i] (as
// grid_assign_cells) and counts[cells[i]] += 1 (as grid_count_cells) in one launch, for the
// counting build that needs no index array. The counts are added, as grid_count_cells adds.
MASAV_LAYOUT(CellAssignCountParams) {
  GridParams grid;
};

// The second pass: where each cell's run lies in cell order, from the counts: for c < cell_count,
// cell_start[c] = counts[0] + ... + counts[c - 1] and cell_end[c] = cell_start[c] + counts[c]
// (an exclusive scan, reduce-then-scan on every backend). The counts are only read.
MASAV_LAYOUT(CellOffsetParams) {
  uint cell_count;
};
// The GPU backends scan the counts in chunks of this many consecutive cells, one invocation per
// chunk: sum the chunk, scan the sums, then scan the chunk again from its offset. No shared
// memory and no barriers: on lavapipe a workgroup-tiled scan of 2M cells took 80 ms, this 15 ms.
MASAV_CONSTANT(kCellOffsetChunk, 16)

// The third pass: point i < n takes a free slot of its cell's run, unsorted[slot] = i, and
// counts[c] goes down by one, so the pass leaves the count table all zero for the next build.
// Which point gets which slot of its cell depends on timing; grid_rank_in_cell fixes the order.
// A cell id past the table, or a cell with no slot left (counts not made from these cells), is
// reported.
MASAV_LAYOUT(CellScatterParams) {
  uint n;
  uint cell_count;
};

// The fourth pass: the point in slot s < n goes to its cell's start plus the number of points of
// its cell with a smaller index, so each cell's run is in increasing index -- the order of the
// stable radix sort, bit for bit. Each invocation reads its whole cell, so a cell may hold at
// most max_per_cell points (validated below the device's loop limit); a fuller cell is reported,
// naming the cell, and so is a slot outside its point's cell run (inputs of another build).
// grid_rank_and_move takes the same parameters and also moves each point's data to its slot.
MASAV_LAYOUT(CellRankParams) {
  uint n;
  uint cell_count;
  uint max_per_cell;
};

// What a kernel reports through the backend's diagnostics word (kernel_body.h, kernel_base.glsl):
// the flag, and the smallest index that raised it. Each flag belongs to one kernel, so the
// message (raise_diagnostics, engine/kernels/kernel_checks.cpp) names it whichever backend ran.
MASAV_CONSTANT(kDiagGatherIndexOutOfRange, 1)  // gather: order[i] past the source
MASAV_CONSTANT(kDiagNeighborOverflow, 2)       // grid_count_neighbors: over max_candidates
MASAV_CONSTANT(kDiagCellOutOfRange, 4)         // grid_count_cells: cells[i] >= cell_count
MASAV_CONSTANT(kDiagScatterNoSlot, 8)          // grid_scatter_cells: cell past the table or full
MASAV_CONSTANT(kDiagCellOverfull, 16)      // grid_rank_in_cell: over max_per_cell (detail: cell)
MASAV_CONSTANT(kDiagRankOutsideCell, 32)   // grid_rank_in_cell: slot outside its cell's run
MASAV_CONSTANT(kDiagMoveCellOverfull, 64)  // grid_rank_and_move: as kDiagCellOverfull
MASAV_CONSTANT(kDiagMoveOutsideCell, 128)  // grid_rank_and_move: as kDiagRankOutsideCell

MASAV_NAMESPACE_END

#ifdef __cplusplus
#include <string>

#include "engine/core/buffer.h"
#include "engine/core/error.h"

namespace masav {

MASAV_LAYOUT_CHECK(GridParams, 48, (origin, 0), (cell_size, 12), (dims, 16), (n, 28),
                   (inv_cell, 32))
MASAV_LAYOUT_CHECK(NeighborParams, 64, (grid, 0), (radius, 48), (radius2, 52), (max_candidates, 56))
MASAV_LAYOUT_CHECK(GatherLayout, 16, (n, 0), (src_count, 4))
MASAV_LAYOUT_CHECK(CellCountParams, 16, (n, 0), (cell_count, 4))
MASAV_LAYOUT_CHECK(CellAssignCountParams, 48, (grid, 0))
MASAV_LAYOUT_CHECK(CellOffsetParams, 16, (cell_count, 0))
MASAV_LAYOUT_CHECK(CellScatterParams, 16, (n, 0), (cell_count, 4))
MASAV_LAYOUT_CHECK(CellRankParams, 16, (n, 0), (cell_count, 4), (max_per_cell, 8))

GridParams make_grid_params(Vec3f origin, float cell_size, UVec3 dims, uint32_t n);
uint64_t grid_cell_count(const GridParams& g);
uint32_t grid_key_bits(const GridParams& g);  // bits needed for the largest cell id
NeighborParams make_neighbor_params(const GridParams& grid, float radius);
// What a neighbour overflow's message names.
inline uint32_t diag_limit(const NeighborParams& p) {
  return p.max_candidates;
}

// dst[i] = src[order[i]] for i < n.
struct GatherParams {
  uint32_t n = 0;
};

template <class F>
GatherLayout device_params(const GatherParams& p, const Buffer<uint32_t>&, const BufferImpl& src,
                           const BufferImpl&) {
  return GatherLayout{p.n, uint32_t(src.count())};
}

class DeviceApi;
inline void validate(const DeviceApi&, const CellCountParams& p, const Buffer<uint32_t>& cells,
                     const Buffer<uint32_t>& counts) {
  if (p.n > cells.size())
    throw_invalid("grid_count_cells", "n", std::to_string(p.n),
                  "at most the cell buffer's size " + std::to_string(cells.size()));
  if (p.cell_count < 1 || p.cell_count > counts.size())
    throw_invalid("grid_count_cells", "cell_count", std::to_string(p.cell_count),
                  "in [1, the count buffer's size " + std::to_string(counts.size()) + "]");
}
// What a cell out of range names.
inline uint32_t diag_limit(const CellCountParams& p) {
  return p.cell_count;
}
// What an overfull cell names.
inline uint32_t diag_limit(const CellRankParams& p) {
  return p.max_per_cell;
}

// Checked before any backend runs the kernel (engine/kernels/kernel_checks.cpp); each throws
// masav::Error naming the kernel, the field, its value and the allowed range.
void validate(const DeviceApi& dev, const GridParams& g, const Buffer<Real4>& positions,
              const Buffer<uint32_t>& cells, const Buffer<uint32_t>& indices);
void validate(const DeviceApi& dev, const GridParams& g, const Buffer<uint32_t>& sorted_cells,
              const Buffer<uint32_t>& cell_start, const Buffer<uint32_t>& cell_end);
void validate(const DeviceApi& dev, const GatherParams& p, const Buffer<uint32_t>& order,
              const BufferImpl& src, const BufferImpl& dst);
void validate(const DeviceApi& dev, const NeighborParams& p, const Buffer<Real4>& positions,
              const Buffer<uint32_t>& cell_start, const Buffer<uint32_t>& cell_end,
              const Buffer<uint32_t>& counts);
void validate(const DeviceApi& dev, const CellAssignCountParams& p, const Buffer<Real4>& positions,
              const Buffer<uint32_t>& cells, const Buffer<uint32_t>& counts);
void validate(const DeviceApi& dev, const CellOffsetParams& p, const Buffer<uint32_t>& counts,
              const Buffer<uint32_t>& cell_start, const Buffer<uint32_t>& cell_end);
void validate(const DeviceApi& dev, const CellScatterParams& p, const Buffer<uint32_t>& cells,
              const Buffer<uint32_t>& cell_end, const Buffer<uint32_t>& counts,
              const Buffer<uint32_t>& unsorted);
void validate(const DeviceApi& dev, const CellRankParams& p, const Buffer<uint32_t>& cells,
              const Buffer<uint32_t>& unsorted, const Buffer<uint32_t>& cell_start,
              const Buffer<uint32_t>& cell_end, const Buffer<uint32_t>& sorted_cells,
              const Buffer<uint32_t>& sorted_index);
void validate(const DeviceApi& dev, const CellRankParams& p, const Buffer<uint32_t>& cells,
              const Buffer<uint32_t>& unsorted, const Buffer<uint32_t>& cell_start,
              const Buffer<uint32_t>& cell_end, const Buffer<uint32_t>& sorted_cells,
              const Buffer<uint32_t>& sorted_index, const Buffer<Real4>& a,
              const Buffer<Real4>& a_sorted, const Buffer<Real4>& b, const Buffer<Real4>& b_sorted,
              const Buffer<uint32_t>& ids, const Buffer<uint32_t>& ids_sorted);

}  // namespace masav
#endif
#endif
