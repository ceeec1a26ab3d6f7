// masav: simulate and render physics on any GPU, with backends that check each other.
#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "app/build_info.h"
#include "app/commands.h"
#include "engine/core/error.h"

int main(int argc, char** argv) {
  CLI::App app{"masav: GPU physics (hydrogen electron cloud, volume ray casting, SPH fluid) on "
               "Vulkan, CUDA and a CPU reference that check each other"};
  app.set_version_flag("--version", fmt::format("masav {} ({})", masav::app::build_info::version,
                                                masav::app::build_info::git));
  app.require_subcommand(1);
  masav::app::add_info_command(app);
  masav::app::add_check_command(app);
  masav::app::add_bench_command(app);
  masav::app::add_atom_command(app);
  masav::app::add_verify_command(app);
  masav::app::add_export_command(app);
  masav::app::add_schema_command(app);
#if MASAV_HAVE_RENDER
  masav::app::add_run_command(app);
  masav::app::add_demo_command(app);
#endif
  masav::app::add_sph_command(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const masav::Error& e) {
    fmt::print(stderr, "masav: error: {}\n", e.what());
    return 1;
  } catch (const std::exception& e) {
    fmt::print(stderr, "masav: unexpected error: {}\n", e.what());
    return 1;
  }
  return 0;
}
