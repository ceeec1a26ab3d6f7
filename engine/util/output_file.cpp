#include "engine/util/output_file.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>

#include "engine/core/error.h"

namespace masav {
namespace {

namespace fs = std::filesystem;

// The chain of links at `path` followed to the path it ends at (which may not exist yet).
std::string follow_links(const std::string& path, std::string_view option) {
  fs::path p(path);
  for (int hops = 0; hops < 40; ++hops) {
    std::error_code ec;
    const fs::file_status s = fs::symlink_status(p, ec);
    if (ec || !fs::is_symlink(s)) return p.string();
    fs::path target = fs::read_symlink(p, ec);
    if (ec)
      throw Error("", std::string(option), fmt::format("cannot read the link '{}': {}", p.string(), ec.message()),
                  "give a regular file or a link masav can read");
    p = target.is_absolute() ? target : p.parent_path() / target;
  }
  throw Error("", std::string(option), fmt::format("'{}' is a loop of symbolic links", path),
              "give a regular file");
}

// Closes `fd`, throwing naming `what` when the close reports a failed write.
void close_checked(int fd, const std::string& what, std::string_view option) {
  if (::close(fd) != 0 && errno != EINTR)
    throw Error("", std::string(option), fmt::format("writing '{}' failed: {}", what, std::strerror(errno)),
                "free disk space or choose another path");
}

}  // namespace

OutputTarget resolve_output(const std::string& path, std::string_view option) {
  OutputTarget t;
  t.path = follow_links(path, option);
  struct stat st {};
  if (::stat(t.path.c_str(), &st) != 0) return t;  // not there yet: created by the rename
  if (S_ISREG(st.st_mode)) return t;
  if (S_ISCHR(st.st_mode) || S_ISFIFO(st.st_mode) || S_ISSOCK(st.st_mode)) {
    t.in_place = true;
    return t;
  }
  const char* what = S_ISDIR(st.st_mode) ? "a directory" : S_ISBLK(st.st_mode) ? "a block device"
                                                                              : "not a regular file";
  throw Error("", std::string(option),
              fmt::format("'{}' is {}: masav writes regular files, devices and pipes only", path, what),
              "give a file name (a device such as /dev/null or a pipe is written in place)");
}

void write_all(int fd, const void* data, size_t bytes, const std::string& what,
               std::string_view option) {
  const char* p = static_cast<const char*>(data);
  size_t done = 0;
  while (done < bytes) {
    const ssize_t n = ::write(fd, p + done, bytes - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0)
      throw Error("", std::string(option),
                  fmt::format("writing '{}' failed: {}", what, n < 0 ? std::strerror(errno) : "nothing written"),
                  "free disk space or choose another path");
    done += size_t(n);
  }
}

void write_output(const std::string& path, std::string_view content, std::string_view option) {
  const OutputTarget t = resolve_output(path, option);
  if (t.in_place) {
    // O_NONBLOCK for the open only: a FIFO without a reader fails instead of waiting forever.
    const int fd = ::open(t.path.c_str(), O_WRONLY | O_CLOEXEC | O_NONBLOCK | O_NOCTTY);
    if (fd < 0)
      throw Error("", std::string(option), fmt::format("cannot open '{}': {}", path, std::strerror(errno)),
                  "check that the device or pipe is writable (a pipe needs a reader)");
    ::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) & ~O_NONBLOCK);
    try {
      write_all(fd, content.data(), content.size(), path, option);
    } catch (...) {
      ::close(fd);
      throw;
    }
    close_checked(fd, path, option);
    return;
  }
  const fs::path target(t.path);
  std::error_code ec;
  if (target.has_parent_path()) fs::create_directories(target.parent_path(), ec);
  const std::string tmp = fmt::format("{}.tmp.{}", t.path, ::getpid());
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC | O_NOFOLLOW, 0644);
  if (fd < 0)
    throw Error("", std::string(option), fmt::format("cannot write '{}': {}", path, std::strerror(errno)),
                "choose a writable output path (check the directory exists and permissions)");
  try {
    write_all(fd, content.data(), content.size(), path, option);
  } catch (...) {
    ::close(fd);
    fs::remove(tmp, ec);
    throw;
  }
  try {
    close_checked(fd, path, option);
  } catch (...) {
    fs::remove(tmp, ec);
    throw;
  }
  if (::rename(tmp.c_str(), t.path.c_str()) != 0) {
    const int e = errno;
    fs::remove(tmp, ec);
    throw Error("", std::string(option),
                fmt::format("cannot rename the temporary file onto '{}': {}", path, std::strerror(e)),
                "choose a writable output path");
  }
}

}  // namespace masav
