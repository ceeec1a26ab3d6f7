#include "engine/scene/stage_cache.h"

#include <fmt/format.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "engine/core/error.h"
#include "engine/util/json_writer.h"

namespace masav::scene {
namespace {

constexpr char kMagic[8] = {'M', 'A', 'S', 'A', 'V', 'S', 'C', '1'};

uint64_t fnv1a(const void* data, size_t n, uint64_t h = 0xcbf29ce484222325ull) {
  const auto* p = static_cast<const uint8_t*>(data);
  for (size_t i = 0; i < n; ++i) h = (h ^ p[i]) * 0x100000001b3ull;
  return h;
}

void put_u64(std::string& out, uint64_t v) {
  out.append(reinterpret_cast<const char*>(&v), 8);
}

bool get_u64(const std::vector<uint8_t>& in, size_t& at, uint64_t& v) {
  if (at + 8 > in.size()) return false;
  std::memcpy(&v, in.data() + at, 8);
  at += 8;
  return true;
}

std::string default_dir() {
  if (const char* d = std::getenv("MASAV_CACHE_DIR"); d && *d) return std::string(d) + "/stages";
  if (const char* x = std::getenv("XDG_CACHE_HOME"); x && *x)
    return std::string(x) + "/masav/stages";
  if (const char* h = std::getenv("HOME"); h && *h) return std::string(h) + "/.cache/masav/stages";
  return "";
}

}  // namespace

StageCache::StageCache(std::string dir) : dir_(dir.empty() ? default_dir() : std::move(dir)) {}

std::string StageCache::key(std::string_view stage, uint32_t format_version, const ParamSet& p,
                            std::span<const std::string> paths) {
  std::string k = fmt::format("{} v{}", stage, format_version);
  for (const auto& path : paths) k += fmt::format(" {}={}", path, format_value(p.get(path)));
  return k;
}

std::string StageCache::path_of(const std::string& key) const {
  return fmt::format("{}/{:016x}.bin", dir_, fnv1a(key.data(), key.size()));
}

std::optional<std::vector<uint8_t>> StageCache::load(const std::string& key) const {
  if (dir_.empty()) return std::nullopt;
  std::ifstream in(path_of(key), std::ios::binary);
  if (!in) return std::nullopt;
  const std::vector<uint8_t> file(std::istreambuf_iterator<char>(in), {});
  if (file.size() < sizeof kMagic || std::memcmp(file.data(), kMagic, sizeof kMagic) != 0)
    return std::nullopt;
  size_t at = sizeof kMagic;
  uint64_t key_len = 0, payload_len = 0, hash = 0;
  if (!get_u64(file, at, key_len) || at + key_len > file.size()) return std::nullopt;
  if (std::string(file.begin() + long(at), file.begin() + long(at + key_len)) != key)
    return std::nullopt;  // another key with the same file name
  at += key_len;
  if (!get_u64(file, at, payload_len) || at + payload_len + 8 > file.size()) return std::nullopt;
  std::vector<uint8_t> payload(file.begin() + long(at), file.begin() + long(at + payload_len));
  at += payload_len;
  if (!get_u64(file, at, hash) || hash != fnv1a(payload.data(), payload.size()))
    return std::nullopt;
  return payload;
}

bool StageCache::store(const std::string& key, std::span<const uint8_t> bytes,
                       std::string* why) const {
  if (dir_.empty()) {
    if (why) *why = "no cache directory (set MASAV_CACHE_DIR or HOME)";
    return false;
  }
  std::string file(kMagic, sizeof kMagic);
  put_u64(file, key.size());
  file += key;
  put_u64(file, bytes.size());
  file.append(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  put_u64(file, fnv1a(bytes.data(), bytes.size()));
  try {
    write_file_atomic(path_of(key), file);
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
