#include "engine/io/writable_paths.h"

#include <fmt/format.h>
#include <unistd.h>

#include <filesystem>

#include "engine/core/error.h"
#include "engine/util/json_writer.h"

namespace masav {

void ensure_writable_dir(const std::string& dir, const std::string& option) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (fs::exists(dir, ec) && !fs::is_directory(dir, ec))
    throw Error("", option, fmt::format("'{}' exists and is not a directory", dir),
                fmt::format("give {} a directory (it holds several files)", option));
  fs::create_directories(dir, ec);
  if (ec || !fs::is_directory(dir, ec))
    throw Error("", option,
                fmt::format("cannot create the output directory '{}'{}", dir,
                            ec ? ": " + ec.message() : ""),
                fmt::format("choose a writable directory with {}", option));
  const std::string probe = fmt::format("{}/.masav_probe_{}", dir, ::getpid());
  try {
    write_file_atomic(probe, "probe\n");
  } catch (const Error&) {
    throw Error("", option, fmt::format("the output directory '{}' is not writable", dir),
                fmt::format("choose a writable directory with {}", option));
  }
  fs::remove(probe, ec);
}

void ensure_writable_file(const std::string& path, const std::string& option) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (fs::is_directory(path, ec))
    throw Error("", option, fmt::format("'{}' is a directory", path),
                fmt::format("give {} a file name", option));
  const fs::path parent = fs::path(path).parent_path();
  ensure_writable_dir(parent.empty() ? std::string(".") : parent.string(), option);
}

}  // namespace masav
