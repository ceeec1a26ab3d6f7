// The one cache-directory resolver (engine/util/cache_dir.h) and the three caches that use it:
// its order, empty values counted as unset, a relative XDG_CACHE_HOME ignored, and an empty
// MASAV_CACHE_DIR never turning into "/" (issue 45, class 6: it wrote the scattering table to
// /scatter/).
#include <doctest/doctest.h>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "engine/atom/scatter_cache.h"
#include "engine/core/error.h"
#include "engine/scene/stage_cache.h"
#include "engine/util/cache_dir.h"
#include "tests/scoped_env.h"
#include "tests/temp_dir.h"

using namespace masav;
namespace fs = std::filesystem;

namespace {

// The three variables the resolver reads, each set (or unset: nullptr) for one case.
struct CacheEnv {
  test::ScopedEnv masav, xdg, home;
  CacheEnv(const char* masav_dir, const char* xdg_dir, const char* home_dir)
      : masav("MASAV_CACHE_DIR", masav_dir),
        xdg("XDG_CACHE_HOME", xdg_dir),
        home("HOME", home_dir) {}
};

std::optional<std::string> resolved() {
  const std::optional<fs::path> d = default_cache_dir();
  return d ? std::optional<std::string>(d->string()) : std::nullopt;
}

bool starts_with(const std::string& s, const std::string& prefix) {
  return s.compare(0, prefix.size(), prefix) == 0;
}

}  // namespace

TEST_CASE("the cache directory: MASAV_CACHE_DIR, then XDG_CACHE_HOME/masav, then ~/.cache/masav") {
  {
    const CacheEnv env("/m", "/x", "/h");
    CHECK(resolved() == "/m");
  }
  {
    const CacheEnv env(nullptr, "/x", "/h");
    CHECK(resolved() == "/x/masav");
  }
  {
    const CacheEnv env(nullptr, nullptr, "/h");
    CHECK(resolved() == "/h/.cache/masav");
  }
  {
    const CacheEnv env(nullptr, nullptr, nullptr);
    CHECK(resolved() == std::nullopt);
  }
  {  // MASAV_CACHE_DIR is taken as given, relative or not
    const CacheEnv env("rel/cache", "/x", "/h");
    CHECK(resolved() == "rel/cache");
  }
}

TEST_CASE("the cache directory: an empty variable is unset, a relative XDG_CACHE_HOME ignored") {
  {
    const CacheEnv env("", "/x", "/h");
    CHECK(resolved() == "/x/masav");
  }
  {
    const CacheEnv env("", "", "/h");
    CHECK(resolved() == "/h/.cache/masav");
  }
  {
    const CacheEnv env("", "", "");
    CHECK(resolved() == std::nullopt);
  }
  {  // the XDG Base Directory specification: a relative path is invalid, and ignored
    const CacheEnv env(nullptr, "relative/cache", "/h");
    CHECK(resolved() == "/h/.cache/masav");
  }
  {
    const CacheEnv env(nullptr, "relative/cache", nullptr);
    CHECK(resolved() == std::nullopt);
  }
}

TEST_CASE("an empty MASAV_CACHE_DIR never makes a cache path outside the directories named") {
  const test::TempDir home("masav_cache_dir_home");
  const std::string named = (home.path / ".cache" / "masav").string();
  for (const char* xdg : {static_cast<const char*>(nullptr), "", "relative"}) {
    CAPTURE(xdg ? xdg : "(unset)");
    {  // HOME set: every cache lies below ~/.cache/masav
      const CacheEnv env("", xdg, home.path.c_str());
      CHECK(resolved() == named);
      const ScatterTableParams p;
      CHECK(starts_with(atom::scatter_cache_path(p), named + "/scatter/"));
      CHECK(scene::StageCache().dir() == named + "/stages");
    }
    {  // nothing named: no cache at all, never "/" or the working directory
      const CacheEnv env("", xdg, "");
      const ScatterTableParams p;
      CHECK(atom::scatter_cache_path(p).empty());
      CHECK_FALSE(atom::load_scatter_cache(p).has_value());
      CHECK_THROWS_WITH_AS(atom::save_scatter_cache(atom::ScatterTable{p, {}, {}, "cpu", 0}),
                           doctest::Contains("no cache directory"), Error);
      CHECK(scene::StageCache().dir().empty());
      std::string why;
      CHECK_FALSE(scene::StageCache().store("key", std::vector<uint8_t>{1}, &why));
      CHECK(why.find("no cache directory") != std::string::npos);
    }
  }
}

TEST_CASE("with MASAV_CACHE_DIR empty the scattering table is cached under HOME, or not at all") {
  const test::TempDir home("masav_cache_dir_table");
  ScatterTableParams p;
  p.rows = 2;
  const size_t n = size_t(p.rows) * (p.bins + kScatterExtras);
  const atom::ScatterTable table{p, std::vector<double>(n, 0.0), std::vector<uint32_t>(n, 0u),
                                 "test", 0};
  {
    const CacheEnv env("", "", home.path.c_str());
    atom::save_scatter_cache(table);
    const fs::path written = atom::scatter_cache_path(p);
    CHECK(written.parent_path() == home.path / ".cache" / "masav" / "scatter");
    CHECK(fs::is_regular_file(written));
    CHECK(atom::load_scatter_cache(p).has_value());
  }
  {  // no directory named: nothing is read, even with a table saved under the old HOME
    const CacheEnv env("", "", "");
    CHECK_FALSE(atom::load_scatter_cache(p).has_value());
  }
}
