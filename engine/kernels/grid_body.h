#pragma once
// grid_assign_cells, grid_count_neighbors and the per-point passes of the counting sort by cell
// (grid_count_cells, grid_scatter_cells, grid_rank_in_cell): one point (or slot) per invocation,
// on the fp32 cell rule and the 27-cell walk of engine/kernels/grid_cell.h. shaders/<kernel>.comp
// are the GLSL twins.
#include "engine/kernels/grid_cell.h"
#include "engine/kernels/grid_params.h"
#include "engine/kernels/kernel_body.h"

namespace masav {

namespace grid {
// A stored position as the fp32 point every backend bins (the CPU reference's doubles rounded).
template <class F>
MASAV_HD inline Point3 point_of(const hd::V4<F>& p) {
  return Point3{float(p.x), float(p.y), float(p.z)};
}
}  // namespace grid

template <>
struct KernelBody<KernelId::grid_assign_cells> {
  static constexpr uint32_t kCpuGrain = 8192;
  // cells[i] = the cell of positions[i], indices[i] = i.
  template <class F, class Diag>
  MASAV_HD static void run(uint32_t i, const GridParams& g, Diag&, const hd::V4<F>* positions,
                           uint32_t* cells, uint32_t* indices) {
    const float origin[3] = {g.origin.x, g.origin.y, g.origin.z};
    const uint32_t dims[3] = {g.dims.x, g.dims.y, g.dims.z};
    const grid::Point3 x = grid::point_of(positions[i]);
    const grid::CellCoord c = grid::point_cell(x.x, x.y, x.z, origin, g.inv_cell, dims);
    cells[i] = grid::cell_id(c.x, c.y, c.z, dims[1], dims[2]);
    indices[i] = i;
  }
};

template <>
struct KernelBody<KernelId::grid_count_neighbors> {
  static constexpr uint32_t kCpuGrain = 1024;
  // counts[i] = points within the radius of sorted point i; a point with more than
  // max_candidates candidates reports kDiagNeighborOverflow.
  template <class F, class Diag>
  MASAV_HD static void run(uint32_t i, const NeighborParams& p, Diag& diag,
                           const hd::V4<F>* positions, const uint32_t* cell_start,
                           const uint32_t* cell_end, uint32_t* counts) {
    const float origin[3] = {p.grid.origin.x, p.grid.origin.y, p.grid.origin.z};
    const uint32_t dims[3] = {p.grid.dims.x, p.grid.dims.y, p.grid.dims.z};
    auto pos_at = [positions](uint32_t j) { return grid::point_of(positions[j]); };
    bool over = false;
    counts[i] = grid::count_neighbors(pos_at(i), pos_at, origin, p.grid.inv_cell, dims, cell_start,
                                      cell_end, p.radius2, p.max_candidates, over);
    if (over) diag.report(kDiagNeighborOverflow, i);
  }
};

template <>
struct KernelBody<KernelId::grid_count_cells> {
  static constexpr uint32_t kCpuGrain = 16384;
  // counts[cells[i]] += 1; integer atomics, so the counts are the same in any order.
  template <class F, class Diag>
  MASAV_HD static void run(uint32_t i, const CellCountParams& p, Diag& diag, const uint32_t* cells,
                           uint32_t* counts) {
    const uint32_t c = cells[i];
    if (c >= p.cell_count) {
      diag.report(kDiagCellOutOfRange, i);
      return;
    }
    hd::atomic_add(&counts[c], 1u);
  }
};

template <>
struct KernelBody<KernelId::grid_assign_count> {
  static constexpr uint32_t kCpuGrain = 8192;
  // cells[i] = the cell of positions[i] (as grid_assign_cells), counts[cells[i]] += 1 (as
  // grid_count_cells; the cell is in range by construction, so nothing is reported).
  template <class F, class Diag>
  MASAV_HD static void run(uint32_t i, const CellAssignCountParams& p, Diag&,
                           const hd::V4<F>* positions, uint32_t* cells, uint32_t* counts) {
    const GridParams& g = p.grid;
    const float origin[3] = {g.origin.x, g.origin.y, g.origin.z};
    const uint32_t dims[3] = {g.dims.x, g.dims.y, g.dims.z};
    const grid::Point3 x = grid::point_of(positions[i]);
    const grid::CellCoord c = grid::point_cell(x.x, x.y, x.z, origin, g.inv_cell, dims);
    const uint32_t cell = grid::cell_id(c.x, c.y, c.z, dims[1], dims[2]);
    cells[i] = cell;
    hd::atomic_add(&counts[cell], 1u);
  }
};

template <>
struct KernelBody<KernelId::grid_scatter_cells> {
  static constexpr uint32_t kCpuGrain = 16384;
  // Point i takes slot cell_end[c] - counts[c] and counts the cell down by one (an atomic add of
  // 2^32 - 1): the cell's points take its slots end - count .. end - 1 once each, in whatever
  // order they arrive, and leave counts[c] at 0.
  template <class F, class Diag>
  MASAV_HD static void run(uint32_t i, const CellScatterParams& p, Diag& diag,
                           const uint32_t* cells, const uint32_t* cell_end, uint32_t* counts,
                           uint32_t* unsorted) {
    const uint32_t c = cells[i];
    if (c >= p.cell_count) {
      diag.report(kDiagScatterNoSlot, i);
      return;
    }
    const uint32_t left = hd::atomic_add(&counts[c], ~0u);
    if (left == 0) {  // no slot left: undo, so the table stays as it was
      hd::atomic_add(&counts[c], 1u);
      diag.report(kDiagScatterNoSlot, i);
      return;
    }
    const uint32_t end = cell_end[c];
    if (left > end || end > p.n) {  // the slot end - left would lie outside [0, n)
      diag.report(kDiagScatterNoSlot, i);
      return;
    }
    unsorted[end - left] = i;
  }
};

namespace grid {
// The rank pass's destination of the point in slot s: its cell's start plus the number of its
// cell's points with a smaller index (a cell's run comes out in increasing index whatever order
// the scatter left). Returns false, reporting `outside` (detail: s) or `overfull` (detail: the
// cell), where the inputs are not one build's or the cell holds more than max_per_cell points.
template <class Diag>
MASAV_HD inline bool rank_slot(uint32_t s, const CellRankParams& p, Diag& diag,
                               const uint32_t* cells, const uint32_t* unsorted,
                               const uint32_t* cell_start, const uint32_t* cell_end,
                               uint32_t outside, uint32_t overfull, uint32_t& point, uint32_t& cell,
                               uint32_t& dest) {
  const uint32_t i = unsorted[s];
  const uint32_t c = i < p.n ? cells[i] : p.cell_count;
  if (c >= p.cell_count || s < cell_start[c] || s >= cell_end[c] || cell_end[c] > p.n) {
    diag.report(outside, s);
    return false;
  }
  const uint32_t first = cell_start[c], last = cell_end[c];
  if (last - first > p.max_per_cell) {
    diag.report(overfull, c);
    return false;
  }
  uint32_t rank = 0;
  for (uint32_t t = first; t < last; ++t) rank += unsorted[t] < i ? 1u : 0u;
  point = i;
  cell = c;
  dest = first + rank;
  return true;
}
}  // namespace grid

template <>
struct KernelBody<KernelId::grid_rank_in_cell> {
  static constexpr uint32_t kCpuGrain = 4096;
  // The point in slot s moves to grid::rank_slot's destination.
  template <class F, class Diag>
  MASAV_HD static void run(uint32_t s, const CellRankParams& p, Diag& diag, const uint32_t* cells,
                           const uint32_t* unsorted, const uint32_t* cell_start,
                           const uint32_t* cell_end, uint32_t* sorted_cells,
                           uint32_t* sorted_index) {
    uint32_t i, c, d;
    if (!grid::rank_slot(s, p, diag, cells, unsorted, cell_start, cell_end, kDiagRankOutsideCell,
                         kDiagCellOverfull, i, c, d))
      return;
    sorted_cells[d] = c;
    sorted_index[d] = i;
  }
};

template <>
struct KernelBody<KernelId::grid_rank_and_move> {
  static constexpr uint32_t kCpuGrain = 4096;
  // grid_rank_in_cell, and point i's two 4-vectors and id move with it to their sorted slot: the
  // three gathers of a simulation's re-sort folded into the rank pass (a scatter from slot order).
  template <class F, class Diag>
  MASAV_HD static void run(uint32_t s, const CellRankParams& p, Diag& diag, const uint32_t* cells,
                           const uint32_t* unsorted, const uint32_t* cell_start,
                           const uint32_t* cell_end, uint32_t* sorted_cells, uint32_t* sorted_index,
                           const hd::V4<F>* a, hd::V4<F>* a_sorted, const hd::V4<F>* b,
                           hd::V4<F>* b_sorted, const uint32_t* ids, uint32_t* ids_sorted) {
    uint32_t i, c, d;
    if (!grid::rank_slot(s, p, diag, cells, unsorted, cell_start, cell_end, kDiagMoveOutsideCell,
                         kDiagMoveCellOverfull, i, c, d))
      return;
    sorted_cells[d] = c;
    sorted_index[d] = i;
    a_sorted[d] = a[i];
    b_sorted[d] = b[i];
    ids_sorted[d] = ids[i];
  }
};

}  // namespace masav
