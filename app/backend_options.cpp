#include <fmt/format.h>

#include "app/commands.h"
#include "app/host_environment.h"
#include "engine/core/error.h"
#include "registry/backends.h"

namespace masav::app {

void add_backend_options(CLI::App& cmd, BackendChoice& choice, bool allow_all) {
  std::vector<std::string> allowed = {"auto", "vulkan", "cuda", "cpu"};
  if (allow_all) allowed.push_back("all");
  cmd.add_option("--backend,-b", choice.backend,
                 allow_all ? "vulkan, cuda, cpu, auto, or all (every available backend)"
                           : "vulkan, cuda, cpu or auto (CUDA if a device, else Vulkan, else CPU)")
      ->check(CLI::IsMember(allowed))
      ->capture_default_str();
  cmd.add_option("--device,-d", choice.device,
                 "device index or part of its name, as `masav info` lists them");
  cmd.add_option("--tune", choice.tune,
                 "a tuning option KEY=VALUE, repeatable (`masav info --tuning` lists them; "
                 "docs/backends.md)")
      ->expected(1)
      ->take_all();
}

Tuning BackendChoice::tuning() const {
  Tuning t;
  for (const std::string& a : tune) set_tuning(t, a);
  return t;
}

std::unique_ptr<Backend> open_backend(const BackendChoice& choice) {
  return open_backend(choice, choice.backend, choice.device);
}

std::unique_ptr<Backend> open_backend(const BackendChoice& choice, const std::string& name,
                                      const std::string& device) {
  const HostRequest request(host_environment(), choice.tuning());
  return create_backend(name, device, request.get());
}

void add_fault_option(CLI::App& cmd, BackendChoice& choice) {
  cmd.add_option("--inject-fault", choice.inject_fault,
                 "a kernel whose output the chosen backend perturbs")
      ->group("");  // a test hook: hidden from --help
}

std::optional<KernelId> fault_kernel(const BackendChoice& choice) {
  const std::string& kernel = choice.inject_fault;
  if (kernel.empty()) return std::nullopt;
  if (auto id = find_kernel(kernel)) return id;
  throw_invalid("", "--inject-fault", kernel, fmt::format("a kernel name: {}", kernel_names_list()));
}

}  // namespace masav::app
