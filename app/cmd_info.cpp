// `masav info`: the backends built into this binary, their devices and limits.
#include <fmt/format.h>

#include "app/build_info.h"
#include "app/commands.h"
#include "app/host_environment.h"
#include "engine/core/error.h"
#include "registry/backends.h"

namespace masav::app {
namespace {

void print_caps(const Capabilities& c) {
  fmt::print("      driver: {}\n", c.driver);
  fmt::print("      subgroup {} (min {}), workgroup <= {}, shared memory {} KiB\n", c.subgroup_size,
             c.min_subgroup_size, c.max_workgroup_size, c.shared_memory_bytes >> 10);
  fmt::print("      largest buffer {}, device memory {} MiB, reals in {}\n",
             c.max_buffer_bytes ? fmt::format("{} MiB", c.max_buffer_bytes >> 20) : "unbounded",
             c.device_memory_bytes >> 20, c.real_is_double ? "fp64" : "fp32");
  if (c.threads > 1) fmt::print("      {} threads\n", c.threads);
}

int run_info(bool details) {
  fmt::print("masav {} ({}), {} {}\n", build_info::version, build_info::git(), build_info::compiler,
             build_info::build_type);
  // Listed through the loader MASAV_VULKAN_LOADER names, as every command opens it.
  const HostRequest request(host_environment());
  const std::string chosen = auto_backend_name(request.get());
  for (const BackendStatus& s : list_backends(request.get())) {
    fmt::print("{:<7} {}{}\n", s.name,
               s.available ? "available" : (s.built ? "unavailable" : "not built"),
               s.name == chosen ? "  <- auto" : "");
    if (!s.reason.empty()) fmt::print("      {}\n", s.reason);
    for (const DeviceStatus& d : s.devices) {
      fmt::print("  [{}] {} ({}; {}){}\n", d.index, d.name, d.type, d.detail,
                 d.usable ? "" : fmt::format(" -- unusable: {}", d.reason));
    }
    if (details && s.available) {
      try {
        auto b = create_backend(s.name, "", request.get());
        fmt::print("    in use: {}\n", b->caps().device_name);
        print_caps(b->caps());
      } catch (const Error& e) {
        fmt::print("    could not open: {}\n", e.what());
      }
    }
  }
  return 0;
}

// Every tuning option (--tune KEY=VALUE), its values and what auto chooses.
void print_tuning() {
  fmt::print("tuning options (--tune KEY=VALUE; docs/backends.md says why each default):\n");
  for (const TuningKey& k : tuning_keys())
    fmt::print("  {:<24} {}\n  {:<24} {}; auto: {}\n", k.key, k.description, "", k.values,
               k.automatic);
}

}  // namespace

void add_info_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("info", "list backends, devices and their limits");
  static bool brief = false, tuning = false;
  cmd->add_flag("--brief", brief, "skip opening each backend for its limits");
  cmd->add_flag("--tuning", tuning, "list the tuning options --tune takes, with their defaults");
  cmd->callback([] {
    if (tuning) return print_tuning();
    if (int rc = run_info(!brief)) throw CLI::RuntimeError(rc);
  });
}

}  // namespace masav::app
