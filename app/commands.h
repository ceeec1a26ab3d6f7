#pragma once
// Subcommands of the masav command line; each registers its options on the CLI11 app.
#include <CLI/CLI.hpp>

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

// Shared --backend / --device options.
struct BackendChoice {
  std::string backend = "auto";
  std::string device;
};
void add_backend_options(CLI::App& cmd, BackendChoice& choice, bool allow_all);

}  // namespace masav::app
