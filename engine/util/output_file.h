#pragma once
// Where a write to a path lands, decided once for every file masav writes. Atomic replacement
// (a temporary file in the same directory, renamed over the path) is for regular files only:
//   - a path that does not exist, or names a regular file: written to a temporary name and
//     renamed over it (an interrupted write never leaves a truncated file);
//   - a symbolic link: resolved to the file it names (the link stays a link), then as above;
//   - a character device, FIFO or socket (/dev/null, /dev/stdout, a pipe): written in place,
//     never replaced, a write error there an error;
//   - a directory, a block device or anything else: refused.
// A rename over /dev/null or over a link would change the machine for every other program, so
// nothing else in masav renames onto a path it did not resolve here.
#include <cstddef>
#include <string>
#include <string_view>

namespace masav {

struct OutputTarget {
  std::string path;       // the file to write: the path itself, or the file its link names
  bool in_place = false;  // a device, FIFO or socket: open and write, never rename onto it
};

// Resolves `path` as above; throws masav::Error naming `option` (the flag or key that gave the
// path) when it is refused or its link cannot be resolved.
OutputTarget resolve_output(const std::string& path, std::string_view option);

// Writes every byte to `fd`, retrying short writes; throws naming `what` (the file) and
// `option` on a failure (a full disk, a closed pipe).
void write_all(int fd, const void* data, size_t bytes, const std::string& what,
               std::string_view option);

// Writes `content` to `path` as resolve_output decides: replaced atomically, or in place. Every
// write is checked through the flush and the close. Throws masav::Error naming `option`.
void write_output(const std::string& path, std::string_view content,
                  std::string_view option = "output");

}  // namespace masav
