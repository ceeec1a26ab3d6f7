#pragma once
// An output directory held by one masav process at a time: two runs writing the same files
// would leave a mix of both. The lock is flock(2) on DIR/.masav.lock, which the kernel releases
// when the holder exits however it exits, so a lock file left by a dead process is simply taken
// over; the file holds the holder's pid for the message.
#include <string>

namespace masav {

class OutputLock {
 public:
  // Locks the existing directory `dir`; throws masav::Error naming `option`, the directory and
  // the other process's pid when another process holds it.
  OutputLock(const std::string& dir, std::string option);
  ~OutputLock();  // removes the lock file and releases the lock
  OutputLock(const OutputLock&) = delete;
  OutputLock& operator=(const OutputLock&) = delete;

  static constexpr const char* kFileName = ".masav.lock";

 private:
  std::string path_;
  int fd_ = -1;
};

}  // namespace masav
