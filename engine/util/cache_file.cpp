#include "engine/util/cache_file.h"

#include <fmt/format.h>

#include <charconv>
#include <filesystem>

#include "engine/core/error.h"
#include "engine/util/bounded_file.h"
#include "engine/util/checked_size.h"
#include "engine/util/checksum.h"
#include "engine/util/json_writer.h"

namespace masav {
namespace {

constexpr std::string_view kMagic = "masav-cache 1\n";

// Everything before the payload line: fixed by the id alone.
std::string id_lines(const CacheFileId& id) {
  if (id.key.find('\n') != std::string::npos || id.kind.find_first_of(" \n") != std::string::npos)
    throw Error("", "cache", fmt::format("the key of a '{}' cache file is not one line", id.kind),
                "report this as a bug");
  return fmt::format("{}kind {} {}\nkey {}\n", kMagic, id.kind, id.version, id.key);
}

}  // namespace

std::string cache_file_header(const CacheFileId& id, std::string_view payload) {
  return fmt::format("{}payload {} fnv1a64 {:016x}\n", id_lines(id), payload.size(),
                     fnv1a64(payload));
}

CacheRead read_cache_file(const std::string& path, const CacheFileId& id,
                          uint64_t max_payload_bytes) {
  CacheRead r;
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) return r;
  try {
    const BoundedFile f(path, "cache file");
    const std::string expect = id_lines(id);
    // The id lines, then at most "payload <20 digits> fnv1a64 <16 hex>\n".
    const std::string head = f.read_some(0, expect.size() + 64);
    if (head.compare(0, kMagic.size(), kMagic) != 0) {
      r.rejected = "not a masav cache file of this version";
      return r;
    }
    if (head.compare(0, expect.size(), expect) != 0) {
      const size_t line_end = head.find('\n', kMagic.size());
      const std::string kind_line = head.substr(kMagic.size(), line_end - kMagic.size());
      r.rejected = kind_line != fmt::format("kind {} {}", id.kind, id.version)
                       ? fmt::format("holds '{}', not 'kind {} {}'", kind_line, id.kind, id.version)
                       : "computed for other parameters: key mismatch";
      return r;
    }
    const size_t eol = head.find('\n', expect.size());
    const std::string line =
        head.substr(expect.size(), eol == std::string::npos ? 0 : eol - expect.size());
    const size_t sp1 = line.find(' '), sp2 = line.find(' ', sp1 + 1), sp3 = line.find(' ', sp2 + 1);
    if (eol == std::string::npos || line.rfind("payload ", 0) != 0 || sp3 == std::string::npos ||
        line.compare(sp2 + 1, sp3 - sp2 - 1, "fnv1a64") != 0 || line.size() - sp3 - 1 != 16) {
      r.rejected = "damaged header: payload line";
      return r;
    }
    const uint64_t bytes = parse_u64(line.substr(sp1 + 1, sp2 - sp1 - 1), path, "payload size");
    uint64_t sum = 0;
    const char* hex = line.data() + sp3 + 1;
    if (std::from_chars(hex, hex + 16, sum, 16).ptr != hex + 16) {
      r.rejected = "damaged header: checksum";
      return r;
    }
    if (bytes > max_payload_bytes) {
      r.rejected = fmt::format("declares {} payload bytes, more than the {} expected", bytes,
                               max_payload_bytes);
      return r;
    }
    const uint64_t start = expect.size() + line.size() + 1;
    if (f.size() != checked_add(start, bytes, path, "payload size")) {
      r.rejected = fmt::format("truncated or extended: {} bytes long, the header says {}", f.size(),
                               start + bytes);
      return r;
    }
    std::string payload = f.read(start, bytes, "payload size");
    if (fnv1a64(payload) != sum) {
      r.rejected = "payload checksum mismatch: the file is damaged";
      return r;
    }
    r.payload = std::move(payload);
  } catch (const std::exception& e) {
    r.rejected = e.what();
  }
  return r;
}

std::optional<std::string> load_cache_file(const std::string& path, const CacheFileId& id,
                                           uint64_t max_payload_bytes) {
  CacheRead r = read_cache_file(path, id, max_payload_bytes);
  if (!r.rejected.empty()) note_cache_rejected(path, r.rejected);
  return std::move(r.payload);
}

void note_cache_rejected(const std::string& path, std::string_view why) {
  fmt::print(stderr, "masav: note: cache file '{}' not used ({}); recomputing\n", path, why);
}

void write_cache_file(const std::string& path, const CacheFileId& id, std::string_view payload) {
  std::string file = cache_file_header(id, payload);
  file.append(payload);
  write_file_atomic(path, file);
}

}  // namespace masav
