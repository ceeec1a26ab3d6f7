#include "engine/grid/hash_grid.h"

#include "engine/core/error.h"
#include "engine/kernels/kernel_checks.h"

namespace masav {

HashGrid make_hash_grid(Backend& backend, const GridParams& params, size_t capacity) {
  check_grid(params, "hash_grid");
  if (params.n > capacity)
    throw_invalid("hash_grid", "n", std::to_string(params.n),
                  "at most the grid's capacity " + std::to_string(capacity));
  const size_t cells = size_t(grid_cell_count(params));
  HashGrid g;
  g.params = params;
  g.sorted_cells = backend.create<uint32_t>(capacity, "grid sorted cells");
  g.sorted_index = backend.create<uint32_t>(capacity, "grid sorted index");
  g.cell_start = backend.create<uint32_t>(cells, "grid cell start");
  g.cell_end = backend.create<uint32_t>(cells, "grid cell end");
  return g;
}

void build_hash_grid(Backend& backend, HashGrid& grid, const Buffer<Real4>& positions,
                     SortImpl sort) {
  const GridParams& g = grid.params;
  backend.grid_assign_cells(g, positions, grid.sorted_cells, grid.sorted_index);
  backend.radix_sort(RadixSortParams{g.n, grid_key_bits(g), sort}, grid.sorted_cells,
                     &grid.sorted_index);
  backend.grid_cell_ranges(g, grid.sorted_cells, grid.cell_start, grid.cell_end);
}

void reorder(Backend& backend, const HashGrid& grid, const BufferImpl& src, BufferImpl& dst) {
  backend.gather({grid.params.n}, grid.sorted_index, src, dst);
}

}  // namespace masav
