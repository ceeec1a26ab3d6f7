#include "engine/sph/sph_kernel_calls.h"

#include <fmt/format.h>

#include "engine/core/error.h"

namespace masav {
namespace {

template <class B>
B& given(const Backend& b, B* buffer, const char* kernel, const char* field) {
  if (!buffer)
    throw Error(b.name(), kernel, fmt::format("no '{}' buffer given", field),
                "pass every buffer the kernel reads or writes");
  return *buffer;
}

// The grid's tables, refused unless they are the counting build's: a radix build leaves an empty
// cell as [0, 0), and a row read as [start of its first cell, end of its last) would then be
// wrong wherever its first cell is empty.
void check_prefix_ranges(const Backend& b, const SphGridView& g, const char* kernel) {
  if (!g.prefix_ranges)
    throw Error(b.name(), kernel, "the grid's cell tables are not prefix ranges (a radix build)",
                "build the grid with GridBuild::counting (build_hash_grid_moving builds it so) "
                "and pass sph_grid_view(grid)");
}

}  // namespace

SphGridView sph_grid_view(const HashGrid& grid) {
  return {&grid.sorted_cells, &grid.cell_start, &grid.cell_end, grid.prefix_ranges};
}

void sph_density(Backend& b, const SphStepParams& p, const SphDensityIO& io) {
  const char* k = "sph_density";
  check_prefix_ranges(b, io.grid, k);
  b.sph_density(p, given(b, io.positions, k, "positions"), given(b, io.grid.cells, k, "cells"),
                given(b, io.grid.cell_start, k, "cell_start"),
                given(b, io.grid.cell_end, k, "cell_end"), given(b, io.density, k, "density"),
                given(b, io.pressure, k, "pressure"), given(b, io.stats, k, "stats"), io.velocities,
                io.neighbor_state, io.reach_rows, io.neighbor_rows);
}

void sph_forces(Backend& b, const SphStepParams& p, const SphForcesIO& io) {
  const char* k = "sph_forces";
  check_prefix_ranges(b, io.grid, k);
  b.sph_forces(p, given(b, io.positions, k, "positions"), given(b, io.velocities, k, "velocities"),
               given(b, io.density, k, "density"), given(b, io.pressure, k, "pressure"),
               given(b, io.grid.cells, k, "cells"), given(b, io.grid.cell_start, k, "cell_start"),
               given(b, io.grid.cell_end, k, "cell_end"), given(b, io.accel, k, "accel"),
               given(b, io.stats, k, "stats"), io.neighbor_state, io.neighbor_rows);
}

void sph_integrate(Backend& b, const SphIntegrateParams& p, const SphIntegrateIO& io) {
  const char* k = "sph_integrate";
  b.sph_integrate(p, io.x0, given(b, io.v0, k, "v0"), io.vk, given(b, io.accel, k, "accel"),
                  io.x_out, given(b, io.v_out, k, "v_out"), io.sum_x, io.sum_v,
                  given(b, io.stats, k, "stats"));
}

void dfsph_factor(Backend& b, const DfsphParams& p, const DfsphIO& io) {
  const char* k = "dfsph_factor";
  check_prefix_ranges(b, io.grid, k);
  b.dfsph_factor(p, given(b, io.positions, k, "positions"), given(b, io.grid.cells, k, "cells"),
                 given(b, io.grid.cell_start, k, "cell_start"),
                 given(b, io.grid.cell_end, k, "cell_end"), given(b, io.factor, k, "factor"),
                 given(b, io.stats, k, "stats"), io.neighbor_rows);
}

void dfsph_rate(Backend& b, const DfsphParams& p, const DfsphIO& io) {
  const char* k = "dfsph_rate";
  check_prefix_ranges(b, io.grid, k);
  b.dfsph_rate(p, given(b, io.positions, k, "positions"), given(b, io.velocities, k, "velocities"),
               given(b, io.density, k, "density"), given(b, io.factor, k, "factor"),
               given(b, io.grid.cells, k, "cells"), given(b, io.grid.cell_start, k, "cell_start"),
               given(b, io.grid.cell_end, k, "cell_end"), given(b, io.kappa, k, "kappa"),
               given(b, io.kappa_sum, k, "kappa_sum"), given(b, io.residual, k, "residual"),
               io.neighbor_rows);
}

void dfsph_correct(Backend& b, const DfsphParams& p, const DfsphIO& io) {
  const char* k = "dfsph_correct";
  check_prefix_ranges(b, io.grid, k);
  b.dfsph_correct(
      p, given(b, io.positions, k, "positions"), given(b, io.kappa, k, "kappa"),
      given(b, io.grid.cells, k, "cells"), given(b, io.grid.cell_start, k, "cell_start"),
      given(b, io.grid.cell_end, k, "cell_end"), given(b, io.velocities, k, "velocities"),
      given(b, io.stats, k, "stats"), io.residual, io.neighbor_rows);
}

}  // namespace masav
