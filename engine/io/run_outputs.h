#pragma once
// A run owns its output directory: the files an earlier run left there under the names this run
// writes (a 30-frame run's frames 5-29 beside a 5-frame run's scene.toml) would read as one run.
// Before writing, a run finds those files and refuses, or with --overwrite removes exactly them
// (names it writes, matched by pattern; never another file, and a link is removed itself, never
// what it names). Its manifest (DIR/manifest.json) then says what the run wrote and whether it
// completed, so a reader never has to guess from the names.
#include <set>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace masav {

// The names a command writes into its directory. In a pattern '#' stands for one or more digits
// ("frame_#.png"); a pattern without one is a fixed name ("scene.toml").
struct OutputNames {
  std::vector<std::string> patterns;
  bool matches(std::string_view name) const;
};

// The files in `dir` (regular files and links, by their own names) that `names` matches, sorted.
std::vector<std::string> find_outputs(const std::string& dir, const OutputNames& names);
// Throws masav::Error naming `option`, how many files of which patterns `dir` holds and
// --overwrite, when it holds any.
void refuse_outputs(const std::string& dir, const OutputNames& names, const std::string& option);
// Removes the files `names` matches in `dir`, except those in `keep`; returns how many.
size_t remove_outputs(const std::string& dir, const OutputNames& names,
                      const std::set<std::string>& keep = {});
// Before a run writes: refuse_outputs, or with `overwrite` remove_outputs.
void claim_outputs(const std::string& dir, const OutputNames& names, bool overwrite,
                   const std::string& option);

// DIR/manifest.json: what the run was (`about`: command, scene, ...), the files it wrote with
// their sizes, and how it ended. Written atomically by write(); a manifest never written by the
// time it is destroyed (an error unwound the run) is written then, as failed.
class RunManifest {
 public:
  static constexpr const char* kFileName = "manifest.json";
  RunManifest(std::string dir, std::vector<std::pair<std::string, std::string>> about);
  ~RunManifest();
  RunManifest(const RunManifest&) = delete;
  RunManifest& operator=(const RunManifest&) = delete;

  void add(const std::string& name);  // a file of the directory the run wrote (once listed)
  // `ended`: "completed", "interrupted" or "failed". May be called again (the last one stands).
  void write(const std::string& ended);

 private:
  std::string dir_;
  std::vector<std::pair<std::string, std::string>> about_;
  std::vector<std::string> files_;
  std::set<std::string> listed_;
  bool written_ = false;
};

}  // namespace masav
