#include "engine/util/cache_dir.h"

#include <cstdlib>
#include <string_view>

namespace masav {
namespace {

// The variable's value, or none when it is unset or empty.
std::optional<std::filesystem::path> variable(const char* name) {
  const char* v = std::getenv(name);
  if (!v || std::string_view(v).empty()) return std::nullopt;
  return std::filesystem::path(v);
}

}  // namespace

std::optional<std::filesystem::path> default_cache_dir() {
  if (auto dir = variable("MASAV_CACHE_DIR")) return dir;
  if (auto xdg = variable("XDG_CACHE_HOME"); xdg && xdg->is_absolute()) return *xdg / "masav";
  if (auto home = variable("HOME")) return *home / ".cache" / "masav";
  return std::nullopt;
}

}  // namespace masav
