#include "engine/io/staged_files.h"

#include <fmt/format.h>
#include <unistd.h>

#include <filesystem>

#include "engine/core/error.h"

namespace masav {

StagedFiles::~StagedFiles() {
  if (committed_) return;
  std::error_code ec;
  for (const auto& [tmp, final_path] : staged_) std::filesystem::remove(tmp, ec);
}

std::string StagedFiles::stage(const std::string& name) {
  const std::string tmp = fmt::format("{}/.{}.staged.{}", dir_, name, ::getpid());
  staged_.emplace_back(tmp, fmt::format("{}/{}", dir_, name));
  return tmp;
}

void StagedFiles::commit() {
  namespace fs = std::filesystem;
  std::error_code ec;
  for (const auto& [tmp, final_path] : staged_) {
    if (!fs::is_regular_file(tmp, ec))
      throw Error("", "output", fmt::format("'{}' was never written", final_path),
                  "internal error: report it");
    if (fs::is_directory(final_path, ec))
      throw Error("", "output", fmt::format("cannot replace the directory '{}'", final_path),
                  "move it away or choose another output directory");
  }
  // Renames within one directory need no space, so once every file is written they succeed.
  for (const auto& [tmp, final_path] : staged_) {
    fs::rename(tmp, final_path, ec);
    if (ec)
      throw Error("", "output",
                  fmt::format("cannot rename '{}' onto '{}': {}", tmp, final_path, ec.message()),
                  "choose a writable output directory");
  }
  committed_ = true;
}

}  // namespace masav
