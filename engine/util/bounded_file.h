#pragma once
// Files masav reads, bounded before they are read. Only regular files are opened: a device
// (/dev/zero, /dev/urandom), a FIFO or a socket never ends and is refused by name. The size is
// known before anything is allocated, so a declared size is checked against the file first, and
// text inputs (scene files, volume headers, transfer functions, scripts) have a size limit.
#include <cstdint>
#include <string>
#include <string_view>

namespace masav {

// The most a text input may hold: 16 MiB, far above any real scene file or header.
inline constexpr uint64_t kMaxTextInputBytes = uint64_t(16) << 20;

class BoundedFile {
 public:
  // Throws Error naming `what` and the path when the path does not exist, is a directory, is not a
  // regular file, or cannot be opened. Never blocks (a FIFO is refused before it is opened).
  BoundedFile(std::string path, std::string_view what);
  ~BoundedFile();
  BoundedFile(const BoundedFile&) = delete;
  BoundedFile& operator=(const BoundedFile&) = delete;

  uint64_t size() const { return size_; }
  const std::string& path() const { return path_; }

  // Exactly bytes [offset, offset + count): when they are not all in the file, an Error naming
  // `field` (the header field that declared them) is thrown before any allocation.
  std::string read(uint64_t offset, uint64_t count, std::string_view field) const;
  // Bytes from offset to the end of the file, at most max_count of them.
  std::string read_some(uint64_t offset, uint64_t max_count) const;

 private:
  std::string path_, what_;
  int fd_ = -1;
  uint64_t size_ = 0;
};

// The whole of a regular file of at most max_bytes (an Error naming the limit otherwise).
std::string read_bounded_file(const std::string& path, std::string_view what,
                              uint64_t max_bytes = kMaxTextInputBytes);

}  // namespace masav
