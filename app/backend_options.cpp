#include "app/commands.h"

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
}

}  // namespace masav::app
