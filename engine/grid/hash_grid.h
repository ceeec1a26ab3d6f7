#pragma once
// The sorted hash grid (thesis §4.2.2) built from the backend's kernels: assign cells, put the
// points in cell order, mark each cell's range. Later kernels reorder per-point arrays with
// reorder() and walk neighbours with grid::for_each_neighbor_cell (C++/CUDA) or
// grid_neighbor_cell (GLSL).
#include "engine/kernels/backend.h"

namespace masav {

struct HashGrid {
  GridParams params;
  Buffer<uint32_t> sorted_cells;  // cell of each point, in sorted order
  Buffer<uint32_t> sorted_index;  // original index of each sorted point
  Buffer<uint32_t> cell_start;    // first sorted point of each cell
  Buffer<uint32_t> cell_end;      // one past the last (== start for empty cells)
  // Set by the counting build, cleared by the radix build: every cell, empty or not, reads
  // [k, k + count) with k the points in lower cells, so cell_end[c] == cell_start[c + 1].
  bool prefix_ranges = false;
  // The counting build's working buffers, made by its first build, so radix builds never pay:
  Buffer<uint32_t> counts;       // per cell, all zero between builds (counted up, scattered down)
  Buffer<uint32_t> point_cells;  // cell of each point, in point order
  Buffer<uint32_t> unsorted;     // the points in cell order, in any order within a cell
};

// How build_hash_grid puts the points in cell order. Both give the same sorted_cells and
// sorted_index bit for bit (cells ascending, within a cell the points in increasing original
// index) and the same ranges for non-empty cells; an empty cell reads [0, 0) after the radix
// build and [k, k) after the counting build (k: the points in lower cells).
enum class GridBuild : uint8_t {
  // Radix sort of (cell, index) pairs on the cell bits in use, then the cell ranges: any number
  // of points per cell, ~15 dispatches on Vulkan.
  radix,
  // Counting sort: count per cell, scan the counts into the ranges, scatter, then rank each
  // point within its cell: 6-7 dispatches, but every cell must hold at most max_per_cell points.
  counting,
};

struct GridBuildOptions {
  GridBuild method = GridBuild::radix;
  uint32_t max_per_cell = 0;           // counting: a fuller cell is an error (grid_rank_in_cell)
  SortImpl sort = SortImpl::portable;  // radix: which sort
};

// Allocates the grid's buffers for up to `capacity` points (params.n may be smaller later).
HashGrid make_hash_grid(Backend& backend, const GridParams& params, size_t capacity);
void build_hash_grid(Backend& backend, HashGrid& grid, const Buffer<Real4>& positions,
                     const GridBuildOptions& options = {});
// The counting build of `positions` that also moves each point's data into cell order on the
// way (grid_rank_and_move): positions -> positions_sorted, b -> b_sorted, ids -> ids_sorted,
// what build_hash_grid followed by three reorder() calls gives, in one pass fewer three.
struct MovedArrays {
  Buffer<Real4>* positions_sorted = nullptr;
  const Buffer<Real4>* b = nullptr;
  Buffer<Real4>* b_sorted = nullptr;
  const Buffer<uint32_t>* ids = nullptr;
  Buffer<uint32_t>* ids_sorted = nullptr;
};
void build_hash_grid_moving(Backend& backend, HashGrid& grid, const Buffer<Real4>& positions,
                            uint32_t max_per_cell, const MovedArrays& moved);
// dst[i] = src[sorted_index[i]]: per-point arrays in cell order.
void reorder(Backend& backend, const HashGrid& grid, const BufferImpl& src, BufferImpl& dst);

}  // namespace masav
