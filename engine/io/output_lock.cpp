#include "engine/io/output_lock.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <string_view>

#include "engine/core/error.h"

namespace masav {
namespace {

std::string read_holder(int fd) {
  char buf[32] = {};
  const ssize_t n = ::pread(fd, buf, sizeof(buf) - 1, 0);
  std::string_view s(buf, n > 0 ? size_t(n) : 0);
  while (!s.empty() && (s.back() == '\n' || s.back() == ' ')) s.remove_suffix(1);
  return s.empty() ? std::string("unknown") : std::string(s);
}

// True when `path` still names the file open as `fd`: a holder that was releasing the lock may
// have removed it between our open and our flock, and a lock on a removed file guards nothing.
bool still_named(int fd, const std::string& path) {
  struct stat a {
  }, b{};
  return ::fstat(fd, &a) == 0 && ::stat(path.c_str(), &b) == 0 && a.st_dev == b.st_dev &&
         a.st_ino == b.st_ino;
}

}  // namespace

OutputLock::OutputLock(const std::string& dir, std::string option) : path_(dir + "/" + kFileName) {
  for (int attempt = 0; attempt < 8; ++attempt) {
    const int fd = ::open(path_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd < 0)
      throw Error("", option,
                  fmt::format("cannot create the lock file '{}': {}", path_, std::strerror(errno)),
                  fmt::format("choose a writable directory with {}", option));
    if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
      const int err = errno;
      if (err != EWOULDBLOCK) {  // a file system without locks: write unguarded
        ::close(fd);
        return;
      }
      const std::string holder = read_holder(fd);
      ::close(fd);
      throw Error("", option,
                  fmt::format("the output directory '{}' is in use by another masav process "
                              "(pid {})",
                              dir, holder),
                  fmt::format("wait for it to finish or choose another directory with {}", option));
    }
    if (!still_named(fd, path_)) {
      ::close(fd);
      continue;
    }
    const std::string pid = fmt::format("{}\n", ::getpid());
    if (::ftruncate(fd, 0) != 0 || ::pwrite(fd, pid.data(), pid.size(), 0) != ssize_t(pid.size())) {
      // The lock holds without the pid; only the message of a second run loses it.
    }
    fd_ = fd;
    return;
  }
  throw Error("", option, fmt::format("cannot lock the output directory '{}'", dir),
              "another process keeps creating and removing its lock file: retry");
}

OutputLock::~OutputLock() {
  if (fd_ < 0) return;
  ::unlink(path_.c_str());  // while still held, so no one locks a file about to vanish
  ::close(fd_);
}

}  // namespace masav
