#pragma once
// Output paths proved usable before any work that would be lost if they were not: a directory
// created if needed and shown writable by a probe file, a file's directory likewise. Errors name
// the option (or scene key) that gave the path.
#include <string>

namespace masav {

// Creates `dir` if needed and proves it writable (a probe file, written then removed).
void ensure_writable_dir(const std::string& dir, const std::string& option);
// Proves that the file `path` can be written (its directory created if needed, writable, and
// the path not a directory).
void ensure_writable_file(const std::string& path, const std::string& option);

}  // namespace masav
