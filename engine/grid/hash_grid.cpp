#include "engine/grid/hash_grid.h"

#include "engine/core/error.h"
#include "engine/kernels/kernel_checks.h"

namespace masav {
namespace {

void build_by_radix(Backend& backend, HashGrid& grid, const Buffer<Real4>& positions,
                    SortImpl sort) {
  const GridParams& g = grid.params;
  backend.grid_assign_cells(g, positions, grid.sorted_cells, grid.sorted_index);
  backend.radix_sort(RadixSortParams{g.n, grid_key_bits(g), sort}, grid.sorted_cells,
                     &grid.sorted_index);
  backend.grid_cell_ranges(g, grid.sorted_cells, grid.cell_start, grid.cell_end);
}

// The count table is zeroed once, here; every build leaves it zero again.
void make_counting_buffers(Backend& backend, HashGrid& grid) {
  const size_t cells = size_t(grid_cell_count(grid.params));
  const size_t capacity = grid.sorted_cells.size();
  if (!grid.counts || grid.counts.size() < cells) {
    grid.counts = backend.create<uint32_t>(cells, "grid cell counts");
    backend.fill(grid.counts, 0u);
  }
  if (!grid.point_cells || grid.point_cells.size() < capacity) {
    grid.point_cells = backend.create<uint32_t>(capacity, "grid point cells");
    grid.unsorted = backend.create<uint32_t>(capacity, "grid unsorted index");
  }
}

// The counting build's passes before the rank: cells, counts, offsets, scatter.
void count_and_scatter(Backend& backend, HashGrid& grid, const Buffer<Real4>& positions) {
  make_counting_buffers(backend, grid);
  const GridParams& g = grid.params;
  const uint32_t cells = uint32_t(grid_cell_count(g));
  // The cells and their counts in one launch (the counting build needs no index array).
  backend.grid_assign_count({g}, positions, grid.point_cells, grid.counts);
  backend.grid_cell_offsets({cells}, grid.counts, grid.cell_start, grid.cell_end);
  backend.grid_scatter_cells({g.n, cells}, grid.point_cells, grid.cell_end, grid.counts,
                             grid.unsorted);
}

void build_by_counting(Backend& backend, HashGrid& grid, const Buffer<Real4>& positions,
                       uint32_t max_per_cell) {
  count_and_scatter(backend, grid, positions);
  const GridParams& g = grid.params;
  backend.grid_rank_in_cell({g.n, uint32_t(grid_cell_count(g)), max_per_cell}, grid.point_cells,
                            grid.unsorted, grid.cell_start, grid.cell_end, grid.sorted_cells,
                            grid.sorted_index);
  grid.prefix_ranges = true;
}

}  // namespace

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
                     const GridBuildOptions& options) {
  grid.prefix_ranges = false;  // until a counting build completes
  if (options.method == GridBuild::counting)
    build_by_counting(backend, grid, positions, options.max_per_cell);
  else
    build_by_radix(backend, grid, positions, options.sort);
}

void build_hash_grid_moving(Backend& backend, HashGrid& grid, const Buffer<Real4>& positions,
                            uint32_t max_per_cell, const MovedArrays& m) {
  if (!m.positions_sorted || !m.b || !m.b_sorted || !m.ids || !m.ids_sorted)
    throw Error(backend.name(), "hash_grid", "build_hash_grid_moving needs every moved array",
                "pass positions_sorted, b, b_sorted, ids and ids_sorted");
  // The rank pass's cap, before any pass runs.
  check_candidates(backend, max_per_cell, "grid_rank_and_move", "max_per_cell");
  grid.prefix_ranges = false;  // until the build completes
  count_and_scatter(backend, grid, positions);
  const GridParams& g = grid.params;
  backend.grid_rank_and_move({g.n, uint32_t(grid_cell_count(g)), max_per_cell}, grid.point_cells,
                             grid.unsorted, grid.cell_start, grid.cell_end, grid.sorted_cells,
                             grid.sorted_index, positions, *m.positions_sorted, *m.b, *m.b_sorted,
                             *m.ids, *m.ids_sorted);
  grid.prefix_ranges = true;
}

void reorder(Backend& backend, const HashGrid& grid, const BufferImpl& src, BufferImpl& dst) {
  backend.gather({grid.params.n}, grid.sorted_index, src, dst);
}

}  // namespace masav
