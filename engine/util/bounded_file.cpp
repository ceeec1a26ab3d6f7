#include "engine/util/bounded_file.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "engine/core/error.h"
#include "engine/util/checked_size.h"

namespace masav {
namespace {

const char* kind_of(mode_t m) {
  if (S_ISCHR(m)) return "a character device";
  if (S_ISBLK(m)) return "a block device";
  if (S_ISFIFO(m)) return "a FIFO (named pipe)";
  if (S_ISSOCK(m)) return "a socket";
  return "not a regular file";
}

[[noreturn]] void refuse(std::string_view what, std::string problem) {
  throw Error("", std::string(what), std::move(problem), "give the path of a regular file");
}

std::string mib(uint64_t bytes) {
  return fmt::format("{:.1f} MiB", double(bytes) / (1 << 20));
}

}  // namespace

BoundedFile::BoundedFile(std::string path, std::string_view what)
    : path_(std::move(path)), what_(what) {
  // stat before open: opening a FIFO for reading would block until a writer comes.
  struct stat st {};
  if (::stat(path_.c_str(), &st) != 0) {
    if (errno == ENOENT) refuse(what_, fmt::format("'{}' does not exist", path_));
    refuse(what_, fmt::format("cannot read '{}' ({})", path_, std::strerror(errno)));
  }
  if (S_ISDIR(st.st_mode)) refuse(what_, fmt::format("'{}' is a directory", path_));
  if (!S_ISREG(st.st_mode))
    refuse(what_, fmt::format("'{}' is {}, not a regular file: it is not read, since it may never "
                              "end",
                              path_, kind_of(st.st_mode)));
  // O_NONBLOCK: if the path was swapped for a FIFO since the stat, open still returns at once.
  fd_ = ::open(path_.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
  if (fd_ < 0) refuse(what_, fmt::format("cannot read '{}' ({})", path_, std::strerror(errno)));
  if (::fstat(fd_, &st) != 0 || !S_ISREG(st.st_mode)) {
    ::close(fd_);
    refuse(what_, fmt::format("'{}' is not a regular file", path_));
  }
  size_ = uint64_t(st.st_size);
}

BoundedFile::~BoundedFile() {
  if (fd_ >= 0) ::close(fd_);
}

std::string BoundedFile::read(uint64_t offset, uint64_t count, std::string_view field) const {
  const uint64_t end = checked_add(offset, count, what_ + " " + path_, field);
  if (end > size_)
    throw Error("", fmt::format("{} {}", what_, path_),
                fmt::format("{} declares bytes {} to {}, but the file holds {} bytes", field,
                            offset, end, size_),
                fmt::format("check {} against the data (is the file complete?)", field));
  std::string out = read_some(offset, count);
  if (out.size() != count)
    throw Error("", fmt::format("{} {}", what_, path_),
                fmt::format("the file ended after {} of {} bytes (it changed while being read)",
                            out.size(), count),
                "read it again once it is no longer being written");
  return out;
}

std::string BoundedFile::read_some(uint64_t offset, uint64_t max_count) const {
  const uint64_t n = offset >= size_ ? 0 : std::min(max_count, size_ - offset);
  std::string out(size_t(n), '\0');
  size_t got = 0;
  while (got < n) {
    const ssize_t r = ::pread(fd_, out.data() + got, n - got, off_t(offset + got));
    if (r < 0 && errno == EINTR) continue;
    if (r < 0)
      throw Error("", what_, fmt::format("reading '{}' failed ({})", path_, std::strerror(errno)),
                  "check the file and the disk");
    if (r == 0) break;  // the file shrank: the caller sees a short result
    got += size_t(r);
  }
  out.resize(got);
  return out;
}

std::string read_bounded_file(const std::string& path, std::string_view what, uint64_t max_bytes) {
  const BoundedFile f(path, what);
  if (f.size() > max_bytes)
    throw Error("", std::string(what),
                fmt::format("'{}' is {} ({} bytes), over the limit of {} for this input", path,
                            mib(f.size()), f.size(), mib(max_bytes)),
                "give a smaller file (is this the right file?)");
  return f.read(0, f.size(), "file size");
}

}  // namespace masav
