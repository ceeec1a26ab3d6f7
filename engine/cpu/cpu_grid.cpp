// Hash-grid kernels of the CPU reference. The cell of a point is computed in fp32 from the point
// rounded to fp32 -- exactly what a GPU backend computes from its fp32 positions -- so the cell
// assignment is an integer result every backend must reproduce bit for bit.
#include <fmt/format.h>

#include <atomic>
#include <cstring>

#include "engine/cpu/cpu_backend.h"
#include "engine/core/error.h"
#include "engine/core/kernel_checks.h"
#include "engine/kernels/grid_cell.h"

namespace masav::cpu {
namespace {

struct GridArrays {
  float origin[3];
  uint32_t dims[3];
  explicit GridArrays(const GridParams& g)
      : origin{g.origin.x, g.origin.y, g.origin.z}, dims{g.dims.x, g.dims.y, g.dims.z} {}
};

}  // namespace

void CpuBackend::do_grid_assign_cells(const GridParams& g, uint64_t, const Buffer<Real4>& positions,
                                   Buffer<uint32_t>& cells, Buffer<uint32_t>& indices) {
  const auto* pos = own(positions.impl(), "grid_assign_cells").as<double>();
  auto* c = own(cells.impl(), "grid_assign_cells").as<uint32_t>();
  auto* idx = own(indices.impl(), "grid_assign_cells").as<uint32_t>();
  const GridArrays ga(g);
  pool_.parallel_for(g.n, 8192, [&](size_t b, size_t e) {
    for (size_t i = b; i < e; ++i) {
      const grid::CellCoord cc = grid::point_cell(float(pos[4 * i]), float(pos[4 * i + 1]),
                                                  float(pos[4 * i + 2]), ga.origin, g.inv_cell,
                                                  ga.dims);
      c[i] = grid::cell_id(cc.x, cc.y, cc.z, ga.dims[1], ga.dims[2]);
      idx[i] = uint32_t(i);
    }
  });
}

void CpuBackend::do_grid_cell_ranges(const GridParams& g, uint64_t, const Buffer<uint32_t>& sorted_cells,
                                  Buffer<uint32_t>& cell_start, Buffer<uint32_t>& cell_end) {
  const auto* c = own(sorted_cells.impl(), "grid_cell_ranges").as<uint32_t>();
  auto* start = own(cell_start.impl(), "grid_cell_ranges").as<uint32_t>();
  auto* end = own(cell_end.impl(), "grid_cell_ranges").as<uint32_t>();
  std::memset(start, 0, cell_start.size() * 4);
  std::memset(end, 0, cell_end.size() * 4);
  const uint32_t n = g.n;
  pool_.parallel_for(n, 8192, [&](size_t b, size_t e) {
    for (size_t i = b; i < e; ++i) {
      if (i == 0 || c[i] != c[i - 1]) start[c[i]] = uint32_t(i);
      if (i + 1 == n || c[i] != c[i + 1]) end[c[i]] = uint32_t(i + 1);
    }
  });
}

void CpuBackend::do_gather(const GatherParams& p, uint64_t, const Buffer<uint32_t>& order,
                           const BufferImpl& src, BufferImpl& dst) {
  const auto* o = own(order.impl(), "gather").as<uint32_t>();
  const auto& s = own(src, "gather");
  auto& d = own(dst, "gather");
  const size_t eb = elem_bytes(src.kind(), real_bytes()), src_count = src.count();
  std::atomic<size_t> bad{SIZE_MAX};
  pool_.parallel_for(p.n, 8192, [&](size_t b, size_t e) {
    for (size_t i = b; i < e; ++i) {
      if (o[i] >= src_count) {
        size_t expect = SIZE_MAX;
        while (i < (expect = bad.load()) && !bad.compare_exchange_weak(expect, i)) {
        }
        std::memset(d.data() + i * eb, 0, eb);
        continue;
      }
      std::memcpy(d.data() + i * eb, s.data() + size_t(o[i]) * eb, eb);
    }
  });
  if (bad.load() != SIZE_MAX)
    raise_diagnostics(*this, "gather", kDiagGatherIndexOutOfRange, uint32_t(bad.load()), 0);
}

void CpuBackend::do_grid_count_neighbors(const NeighborParams& p, uint64_t,
                                      const Buffer<Real4>& sorted_positions,
                                      const Buffer<uint32_t>& cell_start,
                                      const Buffer<uint32_t>& cell_end,
                                      Buffer<uint32_t>& counts) {
  const auto* pos = own(sorted_positions.impl(), "grid_count_neighbors").as<double>();
  const auto* start = own(cell_start.impl(), "grid_count_neighbors").as<uint32_t>();
  const auto* end = own(cell_end.impl(), "grid_count_neighbors").as<uint32_t>();
  auto* out = own(counts.impl(), "grid_count_neighbors").as<uint32_t>();
  const GridArrays ga(p.grid);
  std::atomic<uint32_t> overflow{UINT32_MAX};
  auto pos_at = [pos](uint32_t j) {
    return grid::Point3{float(pos[4 * j]), float(pos[4 * j + 1]), float(pos[4 * j + 2])};
  };
  pool_.parallel_for(p.grid.n, 1024, [&](size_t b, size_t e) {
    for (size_t i = b; i < e; ++i) {
      bool over = false;
      out[i] = grid::count_neighbors(pos_at(uint32_t(i)), pos_at, ga.origin, p.grid.inv_cell,
                                     ga.dims, start, end, p.radius2, p.max_candidates, over);
      if (over) {
        uint32_t expect = UINT32_MAX;
        while (uint32_t(i) < (expect = overflow.load()) &&
               !overflow.compare_exchange_weak(expect, uint32_t(i))) {
        }
      }
    }
  });
  if (overflow.load() != UINT32_MAX)
    raise_diagnostics(*this, "grid_count_neighbors", kDiagNeighborOverflow, overflow.load(),
                      p.max_candidates);
}

}  // namespace masav::cpu
