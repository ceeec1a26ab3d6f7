#include "engine/io/run_outputs.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <map>

#include "engine/core/error.h"
#include "engine/util/json_writer.h"

namespace masav {
namespace {

namespace fs = std::filesystem;

// `name` against `pattern`, where '#' takes one or more digits (greedily: no pattern has a digit
// right after a '#').
bool match(std::string_view pattern, std::string_view name) {
  size_t p = 0, n = 0;
  while (p < pattern.size()) {
    if (pattern[p] == '#') {
      const size_t start = n;
      while (n < name.size() && std::isdigit(static_cast<unsigned char>(name[n]))) ++n;
      if (n == start) return false;
      ++p;
    } else {
      if (n >= name.size() || name[n] != pattern[p]) return false;
      ++p, ++n;
    }
  }
  return n == name.size();
}

std::string shown(std::string pattern) {
  std::replace(pattern.begin(), pattern.end(), '#', '*');
  return pattern;
}

// A regular file or a link (not followed): the only kinds a run writes, so the only kinds taken.
bool file_or_link(const fs::directory_entry& e) {
  std::error_code ec;
  const fs::file_status s = e.symlink_status(ec);
  return !ec && (fs::is_regular_file(s) || fs::is_symlink(s));
}

}  // namespace

bool OutputNames::matches(std::string_view name) const {
  return std::any_of(patterns.begin(), patterns.end(),
                     [&](const std::string& p) { return match(p, name); });
}

std::vector<std::string> find_outputs(const std::string& dir, const OutputNames& names) {
  std::vector<std::string> found;
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (names.matches(name) && file_or_link(*it)) found.push_back(name);
  }
  if (ec)
    throw Error("", "output", fmt::format("cannot list '{}': {}", dir, ec.message()),
                "choose a readable output directory");
  std::sort(found.begin(), found.end());
  return found;
}

void refuse_outputs(const std::string& dir, const OutputNames& names, const std::string& option) {
  const std::vector<std::string> found = find_outputs(dir, names);
  if (found.empty()) return;
  std::vector<std::string> counts;
  for (const std::string& p : names.patterns) {
    const auto n = std::count_if(found.begin(), found.end(),
                                 [&](const std::string& f) { return match(p, f); });
    if (n > 0) counts.push_back(fmt::format("{} {}", n, shown(p)));
  }
  throw Error("", option,
              fmt::format("the output directory '{}' holds {} files of an earlier run ({}); new "
                          "files beside them would mix the two runs",
                          dir, found.size(), fmt::join(counts, ", ")),
              fmt::format("--overwrite removes those files first (only names masav writes, no "
                          "other file), or choose another directory with {}",
                          option));
}

size_t remove_outputs(const std::string& dir, const OutputNames& names,
                      const std::set<std::string>& keep) {
  size_t removed = 0;
  for (const std::string& name : find_outputs(dir, names)) {
    if (keep.count(name)) continue;
    std::error_code ec;
    fs::remove(fs::path(dir) / name, ec);  // a link: the link itself
    if (ec)
      throw Error("", "--overwrite",
                  fmt::format("cannot remove '{}/{}' of an earlier run: {}", dir, name,
                              ec.message()),
                  "remove it by hand or choose another output directory");
    ++removed;
  }
  return removed;
}

void claim_outputs(const std::string& dir, const OutputNames& names, bool overwrite,
                   const std::string& option) {
  if (overwrite)
    remove_outputs(dir, names);
  else
    refuse_outputs(dir, names, option);
}

RunManifest::RunManifest(std::string dir, std::vector<std::pair<std::string, std::string>> about)
    : dir_(std::move(dir)), about_(std::move(about)) {}

RunManifest::~RunManifest() {
  if (written_) return;
  try {
    write("failed");
  } catch (...) {  // unwinding already: the error that stopped the run is the one to report
  }
}

void RunManifest::add(const std::string& name) {
  if (listed_.insert(name).second) files_.push_back(name);
}

void RunManifest::write(const std::string& ended) {
  JsonWriter j;
  j.begin_object();
  for (const auto& [k, v] : about_) j.field(k, v);
  j.field("complete", ended == "completed");
  j.field("ended", ended);
  j.key("files").begin_array();
  for (const std::string& name : files_) {
    std::error_code ec;
    const uintmax_t bytes = fs::file_size(fs::path(dir_) / name, ec);
    if (ec) continue;  // listed but never written (the run stopped first)
    j.begin_object().field("name", name).field("bytes", uint64_t(bytes)).end_object();
  }
  j.end_array().end_object();
  written_ = true;  // a failed write is not retried by the destructor
  write_file_atomic((fs::path(dir_) / kFileName).string(), j.str() + "\n");
}

}  // namespace masav
