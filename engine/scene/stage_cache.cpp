#include "engine/scene/stage_cache.h"

#include <fmt/format.h>

#include <filesystem>

#include "engine/core/error.h"
#include "engine/util/cache_file.h"
#include "engine/util/checksum.h"

namespace masav::scene {
namespace {

// Stage outputs are small by design (see the header); a file declaring more is not read.
constexpr uint64_t kMaxStageOutputBytes = uint64_t(1) << 30;

CacheFileId cache_id(const std::string& key) {
  return {"stage-output", 1, key};
}

}  // namespace

StageCache::StageCache(std::string dir) : dir_(std::move(dir)) {}

std::string StageCache::key(std::string_view stage, uint32_t format_version, const ParamSet& p,
                            std::span<const std::string> paths) {
  std::string k = fmt::format("{} v{}", stage, format_version);
  for (const auto& path : paths) k += fmt::format(" {}={}", path, format_value(p.get(path)));
  return k;
}

std::string StageCache::path_of(const std::string& key) const {
  return fmt::format("{}/{:016x}.bin", dir_, fnv1a64(key));
}

std::optional<std::vector<uint8_t>> StageCache::load(const std::string& key) const {
  if (dir_.empty()) return std::nullopt;
  const auto payload = load_cache_file(path_of(key), cache_id(key), kMaxStageOutputBytes);
  if (!payload) return std::nullopt;
  return std::vector<uint8_t>(payload->begin(), payload->end());
}

bool StageCache::store(const std::string& key, std::span<const uint8_t> bytes,
                       std::string* why) const {
  if (dir_.empty()) {
    if (why) *why = "no cache directory (the masav command line takes MASAV_CACHE_DIR or HOME)";
    return false;
  }
  try {
    write_cache_file(path_of(key), cache_id(key),
                     std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
  } catch (const Error& e) {
    if (why) *why = e.what();
    return false;
  }
  return true;
}

CachedStage::CachedStage(const StageCache& cache, std::function<std::string()> key,
                         std::function<std::vector<uint8_t>()> compute,
                         std::function<void(std::span<const uint8_t>)> restore)
    : cache_(cache),
      key_(std::move(key)),
      compute_(std::move(compute)),
      restore_(std::move(restore)) {}

void CachedStage::run() {
  const std::string k = key_();
  if (auto bytes = cache_.load(k)) {
    restore_(*bytes);
    from_cache_ = true;
    return;
  }
  from_cache_ = false;
  const std::vector<uint8_t> out = compute_();
  std::string why;
  if (!cache_.store(k, out, &why))
    fmt::print(stderr, "masav: note: stage output not cached ({})\n", why);
}

}  // namespace masav::scene
