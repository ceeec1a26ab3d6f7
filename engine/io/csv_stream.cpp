#include "engine/io/csv_stream.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>

#include "engine/core/error.h"
#include "engine/util/output_file.h"

namespace masav {
namespace {

std::string partial_for(const std::string& target) {
  const std::filesystem::path p(target);
  return (p.parent_path() / ("." + p.filename().string() + ".masav-partial")).string();
}

}  // namespace

CsvStream::CsvStream(const std::string& path, std::vector<std::string> columns, std::string option)
    : path_(path), option_(std::move(option)), table_(std::move(columns)) {
  const OutputTarget t = resolve_output(path, option_);
  target_ = t.path;
  in_place_ = t.in_place;
  partial_ = in_place_ ? target_ : partial_for(target_);
  // A device is opened as it is (O_NONBLOCK for the open only: a pipe without a reader fails
  // instead of waiting); the partial is never followed through a link someone planted there.
  fd_ = in_place_ ? ::open(partial_.c_str(), O_WRONLY | O_CLOEXEC | O_NOCTTY | O_NONBLOCK)
                  : ::open(partial_.c_str(), O_WRONLY | O_CREAT | O_CLOEXEC | O_NOFOLLOW, 0644);
  if (fd_ < 0)
    throw Error("", option_, fmt::format("cannot create '{}': {}", path, std::strerror(errno)),
                fmt::format("choose a writable file with {}", option_));
  if (in_place_) ::fcntl(fd_, F_SETFL, ::fcntl(fd_, F_GETFL) & ~O_NONBLOCK);
  // Two runs streaming into one file would interleave their rows: the partial is locked before
  // it is truncated, so a second run leaves the first one's rows alone.
  if (!in_place_ && ::flock(fd_, LOCK_EX | LOCK_NB) != 0 && errno == EWOULDBLOCK) {
    ::close(fd_);
    fd_ = -1;
    throw Error("", option_, fmt::format("'{}' is being written by another process", path),
                fmt::format("give each run its own {} file", option_));
  }
  if (!in_place_ && ::ftruncate(fd_, 0) != 0) {
    const int err = errno;
    ::close(fd_);
    fd_ = -1;
    throw Error("", option_, fmt::format("cannot truncate '{}': {}", partial_, std::strerror(err)),
                fmt::format("choose a writable file with {}", option_));
  }
  try {
    flush_pending();  // the header: a file that cannot take it fails before any work
  } catch (...) {
    ::close(fd_);
    fd_ = -1;
    if (!in_place_) ::unlink(partial_.c_str());
    throw;
  }
}

CsvStream::~CsvStream() {
  if (fd_ < 0) return;
  ::close(fd_);
  if (!in_place_ && !committed_) ::unlink(partial_.c_str());
}

void CsvStream::row(const std::vector<double>& values) {
  table_.row(values);
  flush_pending();
  ++rows_;
}

void CsvStream::commit() {
  if (in_place_ || committed_) return;
  if (::fsync(fd_) != 0 || ::rename(partial_.c_str(), target_.c_str()) != 0)
    throw Error("", option_,
                fmt::format("cannot move the rows of '{}' into place: {}", path_, std::strerror(errno)),
                fmt::format("they are in '{}'", partial_));
  committed_ = true;
  partial_ = target_;
}

void CsvStream::flush_pending() {
  const std::string text = table_.take();
  size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = ::write(fd_, text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const std::string why = n < 0 ? std::strerror(errno) : "nothing written";
      // Cut back to the last whole row, so the file never ends in half a row.
      if (!in_place_ && ::ftruncate(fd_, off_t(bytes_)) == 0) ::lseek(fd_, off_t(bytes_), SEEK_SET);
      throw Error("", option_, fmt::format("writing '{}' failed after {} rows: {}", path_, rows_, why),
                  "free disk space or choose another file (the rows before it are in the file)");
    }
    done += size_t(n);
  }
  bytes_ += text.size();
}

}  // namespace masav
