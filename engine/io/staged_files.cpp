#include "engine/io/staged_files.h"

#include <fmt/format.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <vector>

#include "engine/core/error.h"
#include "engine/util/output_file.h"

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
  // Each name resolved first (engine/util/output_file.h): a link is replaced through to its
  // file, a device or pipe written in place, a directory refused, before anything is renamed.
  std::vector<OutputTarget> targets;
  for (const auto& [tmp, final_path] : staged_) {
    if (!fs::is_regular_file(tmp, ec))
      throw Error("", "output", fmt::format("'{}' was never written", final_path),
                  "internal error: report it");
    targets.push_back(resolve_output(final_path, "output"));
  }
  // Renames within one directory need no space, so once every file is written they succeed.
  for (size_t i = 0; i < staged_.size(); ++i) {
    const auto& [tmp, final_path] = staged_[i];
    if (targets[i].in_place) {
      std::ifstream in(tmp, std::ios::binary);
      const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
      write_output(final_path, bytes, "output");
      fs::remove(tmp, ec);
      continue;
    }
    fs::rename(tmp, targets[i].path, ec);
    if (ec)
      throw Error("", "output",
                  fmt::format("cannot rename '{}' onto '{}': {}", tmp, final_path, ec.message()),
                  "choose a writable output directory");
  }
  committed_ = true;
}

}  // namespace masav
