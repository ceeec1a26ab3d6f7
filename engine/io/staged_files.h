#pragma once
// A set of output files that appears complete or not at all: each file is written under a
// temporary name in its directory, and only when every one of them is written are they renamed
// to their names. A failure on the way (a full disk, an exception, an interrupt) leaves the
// directory as it was; the temporary files are removed.
#include <string>
#include <utility>
#include <vector>

namespace masav {

class StagedFiles {
 public:
  explicit StagedFiles(std::string dir) : dir_(std::move(dir)) {}
  ~StagedFiles();  // removes the temporary files of a set never committed
  StagedFiles(const StagedFiles&) = delete;
  StagedFiles& operator=(const StagedFiles&) = delete;

  // The temporary path to write the file `name` (inside the directory) to.
  std::string stage(const std::string& name);
  // Renames every staged file to its name; throws masav::Error when one cannot be.
  void commit();
  const std::string& dir() const { return dir_; }

 private:
  std::string dir_;
  std::vector<std::pair<std::string, std::string>> staged_;  // temporary path, final path
  bool committed_ = false;
};

}  // namespace masav
