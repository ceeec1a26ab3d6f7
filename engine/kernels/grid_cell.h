#pragma once
// Uniform-grid cell math (thesis Eq. 4.1-4.2) and the 27-cell neighbour iteration, shared by the
// CPU reference and CUDA; shaders/common/grid_cell.glsl is the GLSL twin. All in fp32 with one
// rounding per operation so that every backend puts a point in the same cell.
#include <cmath>
#include <cstdint>

#include "engine/core/hd.h"

namespace masav::grid {

// Cell index along one axis: floor((p - origin) * inv_cell) clamped to [0, dim - 1]; NaN -> 0.
MASAV_HD inline uint32_t axis_cell(float p, float origin, float inv_cell, uint32_t dim) {
  const float f = floorf(hd::mul_rn(hd::sub_rn(p, origin), inv_cell));
  if (!(f >= 0.0f)) return 0u;
  if (f >= float(dim - 1u)) return dim - 1u;
  return uint32_t(f);
}

// Thesis Eq. 4.2: HashValue = x * M * N + y * N + z.
MASAV_HD inline uint32_t cell_id(uint32_t cx, uint32_t cy, uint32_t cz, uint32_t dim_y,
                                 uint32_t dim_z) {
  return (cx * dim_y + cy) * dim_z + cz;
}

struct CellCoord {
  uint32_t x, y, z;
};

MASAV_HD inline CellCoord point_cell(float px, float py, float pz, const float origin[3],
                                     float inv_cell, const uint32_t dims[3]) {
  return CellCoord{axis_cell(px, origin[0], inv_cell, dims[0]),
                   axis_cell(py, origin[1], inv_cell, dims[1]),
                   axis_cell(pz, origin[2], inv_cell, dims[2])};
}

// |a - b|^2 as ((dx*dx + dy*dy) + dz*dz), one rounding per operation.
MASAV_HD inline float distance2(float ax, float ay, float az, float bx, float by, float bz) {
  const float dx = hd::sub_rn(bx, ax), dy = hd::sub_rn(by, ay), dz = hd::sub_rn(bz, az);
  return hd::add_rn(hd::add_rn(hd::mul_rn(dx, dx), hd::mul_rn(dy, dy)), hd::mul_rn(dz, dz));
}

// Visits the (up to) 27 cells around `c` that lie inside the grid, x outermost and z innermost,
// calling visit(first, last) with each cell's range [cell_start, cell_end). Every backend walks
// the cells in this order, so sums over neighbours add up in the same order.
template <class Visit>
MASAV_HD inline void for_each_neighbor_cell(CellCoord c, const uint32_t dims[3],
                                            const uint32_t* cell_start, const uint32_t* cell_end,
                                            Visit&& visit) {
  for (int k = 0; k < 27; ++k) {
    const int nx = int(c.x) + k / 9 - 1, ny = int(c.y) + (k / 3) % 3 - 1, nz = int(c.z) + k % 3 - 1;
    if (nx < 0 || ny < 0 || nz < 0 || nx >= int(dims[0]) || ny >= int(dims[1]) ||
        nz >= int(dims[2]))
      continue;
    const uint32_t id = cell_id(uint32_t(nx), uint32_t(ny), uint32_t(nz), dims[1], dims[2]);
    visit(cell_start[id], cell_end[id]);
  }
}

struct Point3 {
  float x, y, z;
};

// Points within sqrt(radius2) of `p` over its 27 cells, examining at most `max_candidates`
// sorted points (sets `overflow` beyond that). pos_at(j) returns sorted point j as Point3.
// The CPU reference and CUDA both run this body; GLSL mirrors it in grid_count_neighbors.comp.
template <class PosAt>
MASAV_HD inline uint32_t count_neighbors(Point3 p, PosAt&& pos_at, const float origin[3],
                                         float inv_cell, const uint32_t dims[3],
                                         const uint32_t* cell_start, const uint32_t* cell_end,
                                         float radius2, uint32_t max_candidates, bool& overflow) {
  const CellCoord c = point_cell(p.x, p.y, p.z, origin, inv_cell, dims);
  uint32_t count = 0, candidates = 0;
  overflow = false;
  for_each_neighbor_cell(c, dims, cell_start, cell_end, [&](uint32_t first, uint32_t last) {
    for (uint32_t j = first; j < last && !overflow; ++j) {
      if (++candidates > max_candidates) {
        overflow = true;
        break;
      }
      const Point3 q = pos_at(j);
      if (distance2(p.x, p.y, p.z, q.x, q.y, q.z) <= radius2) ++count;
    }
  });
  return count;
}

}  // namespace masav::grid
