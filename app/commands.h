#pragma once
// Subcommands of the masav command line; each registers its options on the CLI11 app.
#include <CLI/CLI.hpp>

namespace masav::app {

void add_info_command(CLI::App& app);
void add_check_command(CLI::App& app);
void add_bench_command(CLI::App& app);
void add_atom_command(CLI::App& app);  // also `masav volume`

// Shared --backend / --device options.
struct BackendChoice {
  std::string backend = "auto";
  std::string device;
};
void add_backend_options(CLI::App& cmd, BackendChoice& choice, bool allow_all);

}  // namespace masav::app
