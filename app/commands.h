#pragma once
// Subcommands of the masav command line; each registers its options on the CLI11 app.
#include <CLI/CLI.hpp>
#include <string>

namespace masav::app {

void add_info_command(CLI::App& app);
void add_check_command(CLI::App& app);
void add_bench_command(CLI::App& app);
void add_atom_command(CLI::App& app);  // also `masav volume`
// Scenes: verify, export and schema need no renderer; run and demo draw with Vulkan.
void add_verify_command(CLI::App& app);
void add_export_command(CLI::App& app);
void add_schema_command(CLI::App& app);
void add_run_command(CLI::App& app);
void add_demo_command(CLI::App& app);
void add_sph_command(CLI::App& app);
// `masav bench` subcommands (bench_<name>.cpp), which add_bench_command adds.
void add_sort_bench(CLI::App& bench);
void add_grid_bench(CLI::App& bench);
void add_atom_bench(CLI::App& bench);
void add_scatter_bench(CLI::App& bench);
void add_light_bench(CLI::App& bench);
void add_raymarch_bench(CLI::App& bench);
void add_sph_bench(CLI::App& bench);
void add_dambreak_bench(CLI::App& bench);

// Shared --backend / --device options.
struct BackendChoice {
  std::string backend = "auto";
  std::string device;
};
void add_backend_options(CLI::App& cmd, BackendChoice& choice, bool allow_all);

// Adds subcommand `name`. After parsing, its callback runs `run(o)`; a non-zero result is thrown
// as CLI::RuntimeError, so main's app.exit() stays the one place that ends the process.
template <class Options>
CLI::App* add_command(CLI::App& parent, const std::string& name, const std::string& description,
                      const Options& o, int (*run)(const Options&)) {
  CLI::App* cmd = parent.add_subcommand(name, description);
  cmd->callback([&o, run] {
    if (int rc = run(o)) throw CLI::RuntimeError(rc);
  });
  return cmd;
}

// An option checked against [lo, hi], with its default shown in --help.
template <class T, class Bound>
CLI::Option* add_ranged_option(CLI::App& cmd, const std::string& name, T& value,
                               const std::string& help, Bound lo, Bound hi) {
  return cmd.add_option(name, value, help)->check(CLI::Range(lo, hi))->capture_default_str();
}

}  // namespace masav::app
