#pragma once
// Stage outputs kept on disk between runs, keyed by everything they depend on: for outputs that
// take long to compute and little to store -- the atom scene's scattering table (SPEC §4: "the
// scattering table is cached on disk by its parameters"). Files are written to a temporary name
// and renamed, with a header naming the key and a checksum of the payload
// (engine/util/cache_file.h); a file that is truncated, corrupt, or holds another key is a miss
// with a note, never an error.
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "engine/scene/param_schema.h"
#include "engine/scene/stage_graph.h"

namespace masav::scene {

class StageCache {
 public:
  // The files go straight into `dir` (a caller with a cache root passes <root>/stages,
  // engine/util/cache_dir.h); "" = no cache: nothing is loaded and store() refuses.
  explicit StageCache(std::string dir = "");

  // The key of a stage's output: its name, a format version, and the listed parameters' values.
  static std::string key(std::string_view stage, uint32_t format_version, const ParamSet& p,
                         std::span<const std::string> paths);

  std::optional<std::vector<uint8_t>> load(const std::string& key) const;
  // False (with the reason in `why`) when the cache cannot be written: the run goes on.
  bool store(const std::string& key, std::span<const uint8_t> bytes,
             std::string* why = nullptr) const;
  std::string path_of(const std::string& key) const;
  const std::string& dir() const { return dir_; }

 private:
  std::string dir_;
};

// A stage whose output comes from the cache when it holds the current key: otherwise compute()
// produces it (and its bytes, which are stored); restore() puts cached bytes in place.
class CachedStage final : public Stage {
 public:
  CachedStage(const StageCache& cache, std::function<std::string()> key,
              std::function<std::vector<uint8_t>()> compute,
              std::function<void(std::span<const uint8_t>)> restore);
  void run() override;
  bool loaded_from_cache() const override { return from_cache_; }

 private:
  const StageCache& cache_;
  std::function<std::string()> key_;
  std::function<std::vector<uint8_t>()> compute_;
  std::function<void(std::span<const uint8_t>)> restore_;
  bool from_cache_ = false;
};

}  // namespace masav::scene
