#pragma once
// Subcommands of the masav command line; each registers its options on the CLI11 app.
#include <CLI/CLI.hpp>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "engine/kernels/backend.h"

namespace masav::app {

// Exit statuses (docs/commands.md#exit-status): 0 success; 1 an error, or a cross-check that
// disagrees; kExitNotCompared a cross-check that disagreed nowhere but could not compare a kernel
// (a backend refused it: a buffer over its limit); 130 interrupted.
constexpr int kExitNotCompared = 3;

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
// Triangle meshes for boundaries: read, checked, their signed distance field.
void add_mesh_command(CLI::App& app);
// `masav bench` subcommands (bench_<name>.cpp), which add_bench_command adds.
void add_sort_bench(CLI::App& bench);
void add_grid_bench(CLI::App& bench);
void add_atom_bench(CLI::App& bench);
void add_scatter_bench(CLI::App& bench);
void add_light_bench(CLI::App& bench);
void add_raymarch_bench(CLI::App& bench);
void add_sph_bench(CLI::App& bench);
void add_dambreak_bench(CLI::App& bench);

// Shared --backend / --device / --tune options.
struct BackendChoice {
  std::string backend = "auto";
  std::string device;
  std::vector<std::string> tune;  // key=value, in order (engine/core/tuning.h)
  std::string inject_fault;       // verify, run, demo: see add_fault_option
  Tuning tuning() const;          // the --tune assignments applied (throws on a bad one)
};
void add_backend_options(CLI::App& cmd, BackendChoice& choice, bool allow_all);
// The backend `name` (default: the choice's) on `device` with the choice's tuning.
std::unique_ptr<Backend> open_backend(const BackendChoice& choice);
std::unique_ptr<Backend> open_backend(const BackendChoice& choice, const std::string& name,
                                      const std::string& device);

// The hidden --inject-fault KERNEL of the commands that cross-check (verify, run, demo): the
// chosen backend perturbs that kernel's output during its check, so the tests can prove that a
// mismatch is caught and stops the run.
void add_fault_option(CLI::App& cmd, BackendChoice& choice);
std::optional<KernelId> fault_kernel(const BackendChoice& choice);

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
