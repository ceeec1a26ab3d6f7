#include "engine/io/csv_stream.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "engine/core/error.h"

namespace masav {

CsvStream::CsvStream(const std::string& path, std::vector<std::string> columns, std::string option)
    : path_(path), option_(std::move(option)), table_(std::move(columns)) {
  fd_ = ::open(path.c_str(), O_WRONLY | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ < 0)
    throw Error("", option_, fmt::format("cannot create '{}': {}", path, std::strerror(errno)),
                fmt::format("choose a writable file with {}", option_));
  // Two runs streaming into one file would interleave their rows: it is locked before it is
  // truncated, so a second run leaves the first one's rows alone.
  if (::flock(fd_, LOCK_EX | LOCK_NB) != 0 && errno == EWOULDBLOCK) {
    ::close(fd_);
    fd_ = -1;
    throw Error("", option_, fmt::format("'{}' is being written by another process", path),
                fmt::format("give each run its own {} file", option_));
  }
  if (::ftruncate(fd_, 0) != 0 && errno != EINVAL) {  // EINVAL: a device such as /dev/full
    const int err = errno;
    ::close(fd_);
    fd_ = -1;
    throw Error("", option_, fmt::format("cannot truncate '{}': {}", path, std::strerror(err)),
                fmt::format("choose a writable file with {}", option_));
  }
  try {
    flush_pending();  // the header: a file that cannot take it fails before any work
  } catch (...) {
    ::close(fd_);
    fd_ = -1;
    throw;
  }
}

CsvStream::~CsvStream() {
  if (fd_ >= 0) ::close(fd_);
}

void CsvStream::row(const std::vector<double>& values) {
  table_.row(values);
  flush_pending();
  ++rows_;
}

void CsvStream::flush_pending() {
  const std::string text = table_.take();
  size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = ::write(fd_, text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0)
      throw Error("", option_,
                  fmt::format("writing '{}' failed after {} rows: {}", path_, rows_,
                              n < 0 ? std::strerror(errno) : "nothing written"),
                  "free disk space or choose another file (the rows before it are in the file)");
    done += size_t(n);
  }
}

}  // namespace masav
