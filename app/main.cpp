// masav: simulate and render physics on any GPU, with backends that check each other.
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <string_view>

#include "app/build_info.h"
#include "app/commands.h"
#include "app/mpi_comm.h"
#include "app/number_checks.h"
#include "engine/core/error.h"

namespace {

// CLI11 answers an unknown command word with "A subcommand is required"; this names the word
// and the commands that exist, at the top level and inside `bench`. Returns false after
// printing the error.
bool known_command_words(CLI::App& app, int argc, char** argv) {
  CLI::App* level = &app;
  std::string path = "masav";
  for (int i = 1; i < argc; ++i) {
    const std::string word = argv[i];
    if (word.empty() || word[0] == '-') return true;  // an option: CLI11 checks it
    const auto subs = level->get_subcommands([](const CLI::App*) { return true; });
    if (subs.empty()) return true;
    CLI::App* next = nullptr;
    std::string names;
    for (CLI::App* sub : subs) {
      if (sub->get_name() == word) next = sub;
      names += (names.empty() ? "" : ", ") + sub->get_name();
    }
    if (!next) {
      fmt::print(stderr,
                 "masav: error: unknown command '{} {}'; the commands are: {} (see {} --help)\n",
                 path, word, names, path);
      return false;
    }
    path += " " + word;
    level = next;
  }
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "masav: GPU physics (hydrogen electron cloud, volume ray casting, SPH fluid) on "
      "Vulkan, CUDA and a CPU reference that check each other"};
  app.set_version_flag("--version", fmt::format("masav {} ({})", masav::app::build_info::version,
                                                masav::app::build_info::git()));
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
  masav::app::add_mesh_command(app);
  masav::app::require_finite_numbers(app);
  // The tests' hidden first word: parse and check the command line, run nothing.
  if (argc > 1 && std::string_view(argv[1]) == "--parse-only") {
    masav::app::skip_commands(app);
    argv[1] = argv[0];
    ++argv;
    --argc;
  }
  if (!known_command_words(app, argc, argv)) return 1;
  // mpirun starts one masav per rank: only `masav sph` shares its work among them; any other
  // command would run N times over.
  if (const int ranks = masav::app::launched_ranks();
      ranks > 1 && (argc < 2 || std::string_view(argv[1]) != "sph")) {
    fmt::print(stderr,
               "masav: error: started on {} ranks, but only `masav sph` runs on several ranks; "
               "start other commands without mpirun\n",
               ranks);
    return 1;
  }
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
