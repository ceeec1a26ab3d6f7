#pragma once
// The one place masav decides where its caches live (the scattering table's scatter/, the stage
// outputs' stages/, the Vulkan pipeline cache): each cache adds its own name below this
// directory. The library never reads the process environment: a program (the masav CLI, a test
// main) reads the three variables and passes their values here. In order, the first that
// applies:
//   MASAV_CACHE_DIR          as given
//   $XDG_CACHE_HOME/masav    when XDG_CACHE_HOME is an absolute path (the XDG Base Directory
//                            specification has a relative one ignored)
//   $HOME/.cache/masav       the specification's default
//   none                     nothing is cached: each run recomputes
// A variable set to the empty string counts as unset, so that `MASAV_CACHE_DIR=` (a habit for
// switching a variable off) never makes the cache "/" and masav never writes outside the
// directories named here.
#include <filesystem>
#include <optional>
#include <string>

namespace masav {

// The variables' values as the program found them; "" = unset (or set to "").
struct CacheDirInputs {
  std::string masav_cache_dir;  // MASAV_CACHE_DIR
  std::string xdg_cache_home;   // XDG_CACHE_HOME
  std::string home;             // HOME
};

std::optional<std::filesystem::path> resolve_cache_dir(const CacheDirInputs& in);

}  // namespace masav
