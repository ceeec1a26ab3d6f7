#pragma once
// grid_assign_cells, grid_count_neighbors and grid_count_cells: one point per invocation, on the
// fp32 cell rule and the 27-cell walk of engine/kernels/grid_cell.h. shaders/<kernel>.comp are
// the GLSL twins.
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

}  // namespace masav
