#include "engine/kernels/grid_params.h"

#include <bit>

namespace masav {

GridParams make_grid_params(Vec3f origin, float cell_size, UVec3 dims, uint32_t n) {
  GridParams g;
  g.origin = origin;
  g.cell_size = cell_size;
  g.inv_cell = 1.0f / cell_size;
  g.dims = dims;
  g.n = n;
  return g;
}

uint64_t grid_cell_count(const GridParams& g) {
  return uint64_t(g.dims.x) * uint64_t(g.dims.y) * uint64_t(g.dims.z);
}

uint32_t grid_key_bits(const GridParams& g) {
  uint64_t cells = grid_cell_count(g);
  return cells <= 1 ? 1u : uint32_t(std::bit_width(cells - 1));
}

NeighborParams make_neighbor_params(const GridParams& grid, float radius) {
  NeighborParams p;
  p.grid = grid;
  p.radius = radius;
  p.radius2 = radius * radius;
  return p;
}

}  // namespace masav
