// The one cache-directory resolver (engine/util/cache_dir.h) and the three caches that use it:
// its order, empty values counted as unset, a relative XDG_CACHE_HOME ignored, and an empty
// MASAV_CACHE_DIR never turning into "/" (issue 45, class 6: it wrote the scattering table to
// /scatter/). The resolver takes the variables' values as arguments: only the programs read the
// environment (app/host_environment.h, whose reading is tested last).
#include <doctest/doctest.h>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "app/host_environment.h"
#include "engine/atom/scatter_cache.h"
#include "engine/core/error.h"
#include "engine/scene/stage_cache.h"
#include "engine/util/cache_dir.h"
#include "tests/scoped_env.h"
#include "tests/temp_dir.h"

using namespace masav;
namespace fs = std::filesystem;

namespace {

// MASAV_CACHE_DIR, XDG_CACHE_HOME and HOME as the program found them ("" = unset).
std::optional<std::string> resolved(const std::string& masav_dir, const std::string& xdg,
                                    const std::string& home) {
  const std::optional<fs::path> d = resolve_cache_dir({masav_dir, xdg, home});
  return d ? std::optional<std::string>(d->string()) : std::nullopt;
}

// The directory a program passes on: the resolved one, or "" (no cache).
std::string dir_of(const std::string& masav_dir, const std::string& xdg, const std::string& home) {
  return resolved(masav_dir, xdg, home).value_or("");
}

bool starts_with(const std::string& s, const std::string& prefix) {
  return s.compare(0, prefix.size(), prefix) == 0;
}

}  // namespace

TEST_CASE("the cache directory: MASAV_CACHE_DIR, then XDG_CACHE_HOME/masav, then ~/.cache/masav") {
  CHECK(resolved("/m", "/x", "/h") == "/m");
  CHECK(resolved("", "/x", "/h") == "/x/masav");
  CHECK(resolved("", "", "/h") == "/h/.cache/masav");
  CHECK(resolved("", "", "") == std::nullopt);
  // MASAV_CACHE_DIR is taken as given, relative or not.
  CHECK(resolved("rel/cache", "/x", "/h") == "rel/cache");
}

TEST_CASE("the cache directory: a relative XDG_CACHE_HOME is ignored") {
  // The XDG Base Directory specification: a relative path is invalid, and ignored.
  CHECK(resolved("", "relative/cache", "/h") == "/h/.cache/masav");
  CHECK(resolved("", "relative/cache", "") == std::nullopt);
}

TEST_CASE("an empty MASAV_CACHE_DIR never makes a cache path outside the directories named") {
  const test::TempDir home("masav_cache_dir_home");
  const std::string named = (home.path / ".cache" / "masav").string();
  for (const char* xdg : {"", "relative"}) {
    CAPTURE(xdg);
    {  // HOME set: every cache lies below ~/.cache/masav
      const std::string dir = dir_of("", xdg, home.path.string());
      CHECK(dir == named);
      const ScatterTableParams p;
      CHECK(starts_with(atom::scatter_cache_path(p, dir), named + "/scatter/"));
    }
    {  // nothing named: no cache at all, never "/" or the working directory
      const std::string dir = dir_of("", xdg, "");
      CHECK(dir.empty());
      const ScatterTableParams p;
      CHECK(atom::scatter_cache_path(p, dir).empty());
      CHECK_FALSE(atom::load_scatter_cache(p, dir).has_value());
      CHECK_THROWS_WITH_AS(atom::save_scatter_cache(atom::ScatterTable{p, {}, {}, "cpu", 0}, dir),
                           doctest::Contains("no cache directory"), Error);
    }
  }
}

TEST_CASE("no cache directory given: the caches keep nothing") {
  // The libraries' default is no cache: nothing in them reads MASAV_CACHE_DIR or HOME.
  const test::ScopedEnv masav("MASAV_CACHE_DIR", "/tmp/masav_never_used");
  const ScatterTableParams p;
  CHECK(atom::scatter_cache_path(p).empty());
  CHECK(scene::StageCache().dir().empty());
  std::string why;
  CHECK_FALSE(scene::StageCache().store("key", std::vector<uint8_t>{1}, &why));
  CHECK(why.find("no cache directory") != std::string::npos);
}

TEST_CASE("the scattering table is cached in the directory given, and read from it only") {
  const test::TempDir home("masav_cache_dir_table");
  ScatterTableParams p;
  p.rows = 2;
  const size_t n = size_t(p.rows) * (p.bins + kScatterExtras);
  const atom::ScatterTable table{p, std::vector<double>(n, 0.0), std::vector<uint32_t>(n, 0u),
                                 "test", 0};
  const std::string dir = dir_of("", "", home.path.string());
  atom::save_scatter_cache(table, dir);
  const fs::path written = atom::scatter_cache_path(p, dir);
  CHECK(written.parent_path() == home.path / ".cache" / "masav" / "scatter");
  CHECK(fs::is_regular_file(written));
  CHECK(atom::load_scatter_cache(p, dir).has_value());
  // No directory: nothing is read, even with a table saved under HOME.
  CHECK_FALSE(atom::load_scatter_cache(p, "").has_value());
}

TEST_CASE("the command line's environment: every variable read, empty ones unset") {
  const test::ScopedEnv masav("MASAV_CACHE_DIR", ""), xdg("XDG_CACHE_HOME", "/x"),
      home("HOME", "/h"), device("MASAV_VK_DEVICE", "llvmpipe"),
      validation("MASAV_VK_VALIDATION", "on"), loader("MASAV_VULKAN_LOADER", "/l/libvulkan.so"),
      driver_files("VK_DRIVER_FILES", "/d.json"), icd("VK_ICD_FILENAMES", nullptr);
  const app::HostEnvironment env = app::read_host_environment();
  CHECK(env.cache_dir() == fs::path("/x/masav"));
  CHECK(env.vk_device == "llvmpipe");
  CHECK(env.validation());
  CHECK(env.vulkan_loader == "/l/libvulkan.so");
  CHECK(env.vk_driver_files == "/d.json");
  CHECK(env.vk_icd_filenames.empty());
}

TEST_CASE("the command line's MASAV_VK_VALIDATION: a switch, anything else named in the error") {
  app::HostEnvironment env;
  for (const char* on : {"1", "on", "true"}) {
    env.vk_validation = on;
    CHECK(env.validation());
  }
  for (const char* off : {"", "0", "off", "false"}) {
    env.vk_validation = off;
    CHECK_FALSE(env.validation());
  }
  env.vk_validation = "yes";
  CHECK_THROWS_WITH_AS(env.validation(), doctest::Contains("invalid MASAV_VK_VALIDATION = yes"),
                       Error);
  env = {};
  CHECK(env.cache_dir().empty());  // nothing set: no cache
}
