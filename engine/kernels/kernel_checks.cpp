#include "engine/kernels/kernel_checks.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <initializer_list>

#include "engine/core/error.h"

namespace masav {

void validate(const DeviceApi&, const PhiloxParams&, const Buffer<uint32_t>& out) {
  if (out.size() > UINT32_MAX - 3)
    throw_invalid("philox_u32", "count", std::to_string(out.size()), "below 2^32 - 3");
}

void validate(const DeviceApi&, const PhiloxParams&, const Buffer<float>& out) {
  if (out.size() > UINT32_MAX - 3)
    throw_invalid("philox_uniform", "count", std::to_string(out.size()), "below 2^32 - 3");
}

void validate(const DeviceApi&, const RadixSortParams& p, const Buffer<uint32_t>& keys,
              const Buffer<uint32_t>* values) {
  if (p.key_bits < 1 || p.key_bits > 32)
    throw_invalid("radix_sort", "key_bits", std::to_string(p.key_bits), "in [1, 32]");
  if (p.n > keys.size())
    throw_invalid("radix_sort", "n", std::to_string(p.n),
                  fmt::format("at most the key buffer's size {}", keys.size()));
  if (values && p.n > values->size())
    throw_invalid("radix_sort", "n", std::to_string(p.n),
                  fmt::format("at most the value buffer's size {}", values->size()));
}

void check_grid(const GridParams& g, std::string_view kernel) {
  const std::string where(kernel);
  auto finite = [](float v) { return std::isfinite(v); };
  if (!finite(g.origin.x) || !finite(g.origin.y) || !finite(g.origin.z))
    throw_invalid(where, "origin", fmt::format("({}, {}, {})", g.origin.x, g.origin.y, g.origin.z),
                  "finite");
  if (!finite(g.cell_size) || !(g.cell_size > 0))
    throw_invalid(where, "cell_size", fmt::format("{}", g.cell_size), "finite and > 0");
  if (g.inv_cell != 1.0f / g.cell_size)
    throw_invalid(where, "inv_cell", fmt::format("{}", g.inv_cell),
                  "1/cell_size in fp32 (use make_grid_params)");
  constexpr uint32_t kMaxDim = 1u << 20;  // float(dim - 1) stays exact, ids fit in 31 bits
  for (uint32_t d : {g.dims.x, g.dims.y, g.dims.z})
    if (d < 1 || d > kMaxDim)
      throw_invalid(where, "dims", fmt::format("({}, {}, {})", g.dims.x, g.dims.y, g.dims.z),
                    fmt::format("each in [1, {}]", kMaxDim));
  if (grid_cell_count(g) > (uint64_t(1) << 31))
    throw_invalid(where, "dims", fmt::format("({}, {}, {})", g.dims.x, g.dims.y, g.dims.z),
                  "at most 2^31 cells in all; use a larger cell_size");
}

void validate(const DeviceApi&, const GridParams& g, const Buffer<Real4>& positions,
              const Buffer<uint32_t>& cells, const Buffer<uint32_t>& indices) {
  check_grid(g, "grid_assign_cells");
  if (g.n > positions.size() || g.n > cells.size() || g.n > indices.size())
    throw_invalid("grid_assign_cells", "n", std::to_string(g.n),
                  fmt::format("at most the buffers' sizes (positions {}, cells {}, indices {})",
                              positions.size(), cells.size(), indices.size()));
}

void validate(const DeviceApi&, const CellAssignCountParams& p, const Buffer<Real4>& positions,
              const Buffer<uint32_t>& cells, const Buffer<uint32_t>& counts) {
  const GridParams& g = p.grid;
  check_grid(g, "grid_assign_count");
  if (g.n > positions.size() || g.n > cells.size())
    throw_invalid("grid_assign_count", "n", std::to_string(g.n),
                  fmt::format("at most the buffers' sizes (positions {}, cells {})",
                              positions.size(), cells.size()));
  if (counts.size() < grid_cell_count(g))
    throw_invalid("grid_assign_count", "counts size", std::to_string(counts.size()),
                  fmt::format("at least the grid's {} cells", grid_cell_count(g)));
}

void validate(const DeviceApi&, const GridParams& g, const Buffer<uint32_t>& cells,
              const Buffer<uint32_t>& start, const Buffer<uint32_t>& end) {
  check_grid(g, "grid_cell_ranges");
  const uint64_t ncells = grid_cell_count(g);
  if (start.size() < ncells || end.size() < ncells)
    throw_invalid("grid_cell_ranges", "cell_start/cell_end size",
                  fmt::format("{}/{}", start.size(), end.size()),
                  fmt::format("at least the cell count {}", ncells));
  if (g.n > cells.size())
    throw_invalid("grid_cell_ranges", "n", std::to_string(g.n),
                  fmt::format("at most the cell buffer's size {}", cells.size()));
}

void validate(const DeviceApi& dev, const GatherParams& p, const Buffer<uint32_t>& order,
              const BufferImpl& src, const BufferImpl& dst) {
  if (src.kind() != dst.kind())
    throw Error(dev.name(), "gather",
                fmt::format("source '{}' holds {} but destination '{}' holds {}", src.label(),
                            elem_kind_name(src.kind()), dst.label(), elem_kind_name(dst.kind())),
                "gather between buffers of the same element type");
  if (p.n > order.size() || p.n > dst.count())
    throw_invalid("gather", "n", std::to_string(p.n),
                  fmt::format("at most the sizes of order ({}) and the destination ({})",
                              order.size(), dst.count()));
  if (src.count() > UINT32_MAX)
    throw_invalid("gather", "source size", std::to_string(src.count()), "below 2^32");
}

void validate(const DeviceApi& dev, const NeighborParams& p, const Buffer<Real4>& pos,
              const Buffer<uint32_t>& start, const Buffer<uint32_t>& end,
              const Buffer<uint32_t>& counts) {
  check_grid(p.grid, "grid_count_neighbors");
  if (!std::isfinite(p.radius) || !(p.radius > 0) || p.radius > p.grid.cell_size)
    throw_invalid(
        "grid_count_neighbors", "radius", fmt::format("{}", p.radius),
        fmt::format("in (0, cell_size = {}] so that 27 cells cover the search", p.grid.cell_size));
  if (p.radius2 != p.radius * p.radius)
    throw_invalid("grid_count_neighbors", "radius2", fmt::format("{}", p.radius2),
                  "radius*radius in fp32 (use make_neighbor_params)");
  check_candidates(dev, p.max_candidates, "grid_count_neighbors");
  const uint64_t ncells = grid_cell_count(p.grid);
  if (start.size() < ncells || end.size() < ncells)
    throw_invalid("grid_count_neighbors", "cell_start/cell_end size",
                  fmt::format("{}/{}", start.size(), end.size()),
                  fmt::format("at least the cell count {}", ncells));
  if (p.grid.n > pos.size() || p.grid.n > counts.size())
    throw_invalid("grid_count_neighbors", "n", std::to_string(p.grid.n),
                  fmt::format("at most the buffers' sizes (positions {}, counts {})", pos.size(),
                              counts.size()));
}

namespace {

// The cell count of a counting-sort pass: at least one cell, and a table in every buffer.
void check_cell_count(std::string_view kernel, uint32_t cell_count,
                      std::initializer_list<const Buffer<uint32_t>*> tables) {
  size_t smallest = SIZE_MAX;
  for (const Buffer<uint32_t>* t : tables) smallest = std::min(smallest, t->size());
  if (cell_count < 1 || cell_count > smallest)
    throw_invalid(kernel, "cell_count", std::to_string(cell_count),
                  fmt::format("in [1, the smallest cell table's size {}]", smallest));
}

// n of a counting-sort pass: at most every per-point buffer's size.
void check_point_count(std::string_view kernel, uint32_t n,
                       std::initializer_list<const Buffer<uint32_t>*> per_point) {
  size_t smallest = SIZE_MAX;
  for (const Buffer<uint32_t>* b : per_point) smallest = std::min(smallest, b->size());
  if (n > smallest)
    throw_invalid(kernel, "n", std::to_string(n),
                  fmt::format("at most the smallest per-point buffer's size {}", smallest));
}

}  // namespace

void validate(const DeviceApi&, const CellOffsetParams& p, const Buffer<uint32_t>& counts,
              const Buffer<uint32_t>& start, const Buffer<uint32_t>& end) {
  check_cell_count("grid_cell_offsets", p.cell_count, {&counts, &start, &end});
}

void validate(const DeviceApi&, const CellScatterParams& p, const Buffer<uint32_t>& cells,
              const Buffer<uint32_t>& end, const Buffer<uint32_t>& counts,
              const Buffer<uint32_t>& unsorted) {
  check_point_count("grid_scatter_cells", p.n, {&cells, &unsorted});
  check_cell_count("grid_scatter_cells", p.cell_count, {&end, &counts});
}

void validate(const DeviceApi& dev, const CellRankParams& p, const Buffer<uint32_t>& cells,
              const Buffer<uint32_t>& unsorted, const Buffer<uint32_t>& start,
              const Buffer<uint32_t>& end, const Buffer<uint32_t>& sorted_cells,
              const Buffer<uint32_t>& sorted_index) {
  check_point_count("grid_rank_in_cell", p.n, {&cells, &unsorted, &sorted_cells, &sorted_index});
  check_cell_count("grid_rank_in_cell", p.cell_count, {&start, &end});
  // Each invocation loops over its whole cell: the same budget as a neighbour walk's candidates.
  check_candidates(dev, p.max_per_cell, "grid_rank_in_cell", "max_per_cell");
}

void validate(const DeviceApi& dev, const CellRankParams& p, const Buffer<uint32_t>& cells,
              const Buffer<uint32_t>& unsorted, const Buffer<uint32_t>& start,
              const Buffer<uint32_t>& end, const Buffer<uint32_t>& sorted_cells,
              const Buffer<uint32_t>& sorted_index, const Buffer<Real4>& a,
              const Buffer<Real4>& a_sorted, const Buffer<Real4>& b, const Buffer<Real4>& b_sorted,
              const Buffer<uint32_t>& ids, const Buffer<uint32_t>& ids_sorted) {
  const char* k = "grid_rank_and_move";
  check_point_count(k, p.n, {&cells, &unsorted, &sorted_cells, &sorted_index, &ids, &ids_sorted});
  const size_t smallest = std::min({a.size(), a_sorted.size(), b.size(), b_sorted.size()});
  if (p.n > smallest)
    throw_invalid(k, "n", std::to_string(p.n),
                  fmt::format("at most the smallest per-point buffer's size {}", smallest));
  // Each point's data moves from one array to another: in place, a point would overwrite one
  // that has not moved yet.
  if (&a.impl() == &a_sorted.impl() || &b.impl() == &b_sorted.impl() ||
      &ids.impl() == &ids_sorted.impl())
    throw Error(dev.name(), k, "a source and its sorted destination are the same buffer",
                "move into a second buffer and swap");
  check_cell_count(k, p.cell_count, {&start, &end});
  check_candidates(dev, p.max_per_cell, k, "max_per_cell");
}

uint32_t max_walk_candidates(const DeviceApi& dev) {
  return walk_candidates(dev.caps().max_loop_iterations);
}

void check_candidates(const DeviceApi& dev, uint32_t max_candidates, std::string_view kernel,
                      std::string_view field, uint32_t walks) {
  const uint32_t most = walk_candidates(dev.caps().max_loop_iterations, std::max(walks, 1u));
  if (max_candidates < 1 || max_candidates > most)
    throw_invalid(kernel, field, std::to_string(max_candidates),
                  fmt::format("in [1, {}] (a shader invocation runs at most {} loop iterations "
                              "on {}{})",
                              most, dev.caps().max_loop_iterations, dev.caps().device_name,
                              walks > 1 ? fmt::format(", over {} walks", walks) : ""));
}

void raise_diagnostics(const DeviceApi& dev, uint32_t flags, uint32_t detail, uint32_t limit) {
  if (flags & kDiagGatherIndexOutOfRange)
    throw Error(dev.name(), "gather",
                fmt::format("order[{}] points past the source buffer", detail),
                "pass indices below the source buffer's size");
  if (flags & kDiagNeighborOverflow)
    throw Error(
        dev.name(), "grid_count_neighbors",
        fmt::format("sorted point {} has more than {} candidates in its 27 cells", detail, limit),
        fmt::format("use smaller cells (or fewer points per cell): a shader invocation runs at "
                    "most {} loop iterations on {}",
                    dev.caps().max_loop_iterations, dev.caps().device_name));
  if (flags & kDiagCellOutOfRange)
    throw Error(dev.name(), "grid_count_cells",
                fmt::format("cells[{}] is not below cell_count {}", detail, limit),
                "pass cell ids below cell_count (grid_assign_cells makes them so)");
  if (flags & kDiagScatterNoSlot)
    throw Error(dev.name(), "grid_scatter_cells",
                fmt::format("point {} has no free slot: its cell is past the count table or "
                            "already full",
                            detail),
                "pass the counts grid_count_cells made of the same cells, and cell_end from "
                "grid_cell_offsets of those counts");
  // The rank pass's two failures, in either of its kernels.
  auto rank_failure = [&](const char* kernel, bool overfull, const char* or_else) {
    if (overfull)
      throw Error(dev.name(), kernel,
                  fmt::format("cell {} holds more than max_per_cell = {} points", detail, limit),
                  fmt::format("raise max_per_cell (the SPH scene's max_candidates; at most {}: a "
                              "shader invocation runs at most {} loop iterations on {}){}",
                              max_walk_candidates(dev), dev.caps().max_loop_iterations,
                              dev.caps().device_name, or_else));
    throw Error(dev.name(), kernel,
                fmt::format("slot {} lies outside the cell run of the point it holds", detail),
                "pass unsorted from grid_scatter_cells with the same cells and cell ranges");
  };
  const char* radix = ", use smaller cells, or build the grid with the radix sort";
  if (flags & kDiagCellOverfull) rank_failure("grid_rank_in_cell", true, radix);
  if (flags & kDiagRankOutsideCell) rank_failure("grid_rank_in_cell", false, "");
  if (flags & kDiagMoveCellOverfull)
    rank_failure("grid_rank_and_move", true, " or use smaller cells");
  if (flags & kDiagMoveOutsideCell) rank_failure("grid_rank_and_move", false, "");
}

}  // namespace masav
