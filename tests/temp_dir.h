#pragma once
// A fresh directory under the system's temporary directory for one test, named after the test
// and the process (parallel ctest runs do not share it), removed with everything in it at the end.
#include <unistd.h>

#include <filesystem>
#include <string>
#include <system_error>

namespace masav::test {

struct TempDir {
  std::filesystem::path path;
  explicit TempDir(const std::string& name)
      : path(std::filesystem::temp_directory_path() / (name + "_" + std::to_string(::getpid()))) {
    std::filesystem::remove_all(path);
    std::filesystem::create_directories(path);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  std::string file(const std::string& name) const { return (path / name).string(); }
};

}  // namespace masav::test
