#pragma once
// The sorted hash grid (thesis §4.2.2) built from the backend's kernels: assign cells, sort
// (cell, index) pairs on only the cell bits in use, mark each cell's range. Later kernels reorder
// per-point arrays with reorder() and walk neighbours with grid::for_each_neighbor_cell (C++/CUDA)
// or grid_neighbor_cell (GLSL).
#include "engine/kernels/backend.h"

namespace masav {

struct HashGrid {
  GridParams params;
  Buffer<uint32_t> sorted_cells;  // cell of each point, in sorted order
  Buffer<uint32_t> sorted_index;  // original index of each sorted point
  Buffer<uint32_t> cell_start;    // first sorted point of each cell
  Buffer<uint32_t> cell_end;      // one past the last (== start for empty cells)
};

// Allocates the grid's buffers for up to `capacity` points (params.n may be smaller later).
HashGrid make_hash_grid(Backend& backend, const GridParams& params, size_t capacity);
void build_hash_grid(Backend& backend, HashGrid& grid, const Buffer<Real4>& positions,
                     SortImpl sort = SortImpl::portable);
// dst[i] = src[sorted_index[i]]: per-point arrays in cell order.
void reorder(Backend& backend, const HashGrid& grid, const BufferImpl& src, BufferImpl& dst);

}  // namespace masav
