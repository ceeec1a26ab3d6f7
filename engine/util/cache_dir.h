#pragma once
// The one place masav decides where its caches live (the scattering table's scatter/, the stage
// outputs' stages/, the Vulkan pipeline cache): each cache adds its own name below this
// directory. In order, the first that applies:
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

namespace masav {

std::optional<std::filesystem::path> default_cache_dir();

}  // namespace masav
