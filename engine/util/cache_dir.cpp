#include "engine/util/cache_dir.h"

namespace masav {

std::optional<std::filesystem::path> resolve_cache_dir(const CacheDirInputs& in) {
  namespace fs = std::filesystem;
  if (!in.masav_cache_dir.empty()) return fs::path(in.masav_cache_dir);
  if (const fs::path xdg(in.xdg_cache_home); !xdg.empty() && xdg.is_absolute())
    return xdg / "masav";
  if (!in.home.empty()) return fs::path(in.home) / ".cache" / "masav";
  return std::nullopt;
}

}  // namespace masav
