#pragma once
// Cache files that describe and check themselves. A text header names the container version, the
// kind of payload and its format version, the full key it was computed for, and the payload's
// size and FNV-1a 64 checksum; the payload follows. A file whose header, size or checksum does not
// match is never used: the caller recomputes (and rewrites) it. Files are written to a temporary
// name in the same directory and renamed, so a reader sees a whole file or none.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace masav {

struct CacheFileId {
  std::string kind;      // what the payload is, e.g. "scatter-table"
  uint32_t version = 1;  // the payload's format version: bump it when the layout changes
  std::string key;       // every parameter the payload depends on (one line)
};

struct CacheRead {
  std::optional<std::string> payload;  // the checked payload, when the file was usable
  std::string rejected;  // why a file that exists was not used ("" when absent or used)
};

// The file at `path` for this id. The declared payload size must not exceed max_payload_bytes
// (checked before anything is allocated for it).
CacheRead read_cache_file(const std::string& path, const CacheFileId& id,
                          uint64_t max_payload_bytes);
// read_cache_file, with a one-line note on stderr when an existing file is not used.
std::optional<std::string> load_cache_file(const std::string& path, const CacheFileId& id,
                                           uint64_t max_payload_bytes);
// The one-line note: "masav: note: cache file '<path>' not used (<why>); recomputing".
void note_cache_rejected(const std::string& path, std::string_view why);

// Writes header and payload to a temporary name beside `path`, then renames it onto `path`.
// Throws Error when the cache cannot be written.
void write_cache_file(const std::string& path, const CacheFileId& id, std::string_view payload);

// The header as written for this id and payload (exposed for tests that damage files).
std::string cache_file_header(const CacheFileId& id, std::string_view payload);

}  // namespace masav
