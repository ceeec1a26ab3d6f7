// `masav bench ...`: benchmarks, never tests. Each writes a table and optionally JSON.
#include "app/commands.h"

namespace masav::app {

void add_bench_command(CLI::App& app) {
  auto* bench = app.add_subcommand("bench", "time kernels on each backend (device timestamps)");
  bench->require_subcommand(1);
  add_sort_bench(*bench);
  add_grid_bench(*bench);
  add_atom_bench(*bench);
  add_scatter_bench(*bench);
  add_light_bench(*bench);
  add_raymarch_bench(*bench);
  add_sph_bench(*bench);
  add_dambreak_bench(*bench);
}

}  // namespace masav::app
