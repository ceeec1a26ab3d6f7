// A deterministic fuzz test of scene files and `--set` values: seeded mutants of every shipped
// scene file (bytes flipped, lines dropped, doubled or cut, values replaced by hostile ones:
// huge, negative, NaN, wrapping integers, wrong types) must either load -- and then yield the
// scene's kernels, check inputs and domain settings -- or fail with masav::Error and a message.
// Any other exception fails the test; a crash or a hang fails it as well (ctest's timeout).
// MASAV_FUZZ_MUTANTS sets the number of mutants (the `stress` run uses many more).
#include <doctest/doctest.h>
#include <fmt/format.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "engine/atom/atom_schema.h"
#include "engine/core/error.h"
#include "engine/sph/sph_scene_schema.h"
#include "registry/scene_catalog.h"
#include "registry/scene_file.h"

using namespace masav;

namespace {

namespace fs = std::filesystem;

std::vector<std::pair<std::string, std::string>> shipped_scenes() {
  std::vector<std::pair<std::string, std::string>> out;
  for (const auto& e : fs::directory_iterator(std::string(MASAV_SOURCE_DIR) + "/scenes")) {
    if (e.path().extension() != ".toml") continue;
    std::ifstream in(e.path());
    std::stringstream ss;
    ss << in.rdbuf();
    out.emplace_back(e.path().filename().string(), ss.str());
  }
  std::sort(out.begin(), out.end());
  return out;
}

const std::vector<std::string>& hostile_values() {
  static const std::vector<std::string> v = {"0",
                                             "-1",
                                             "1",
                                             "16",
                                             "65536",
                                             "4000001",
                                             "16777217",
                                             "1e308",
                                             "-1e308",
                                             "1e-308",
                                             "nan",
                                             "inf",
                                             "-inf",
                                             "9223372036854775807",
                                             "-9223372036854775808",
                                             "18446744073709551616",
                                             "4294967312",
                                             "0x7fffffff",
                                             "1_000_000",
                                             "1.5",
                                             "-0.0",
                                             "true",
                                             "false",
                                             "\"\"",
                                             "\"x\"",
                                             "\"state11\"",
                                             "\"custom\"",
                                             "[1, 2]",
                                             "{ a = 1 }",
                                             "1979-05-27",
                                             "'''",
                                             "\"\\u0000\"",
                                             "\"" + std::string(5000, 'a') + "\""};
  return v;
}

using Rng = std::mt19937_64;

size_t pick(Rng& rng, size_t n) {
  return std::uniform_int_distribution<size_t>(0, n - 1)(rng);
}

std::vector<std::string> split_lines(const std::string& s) {
  std::vector<std::string> lines;
  std::stringstream ss(s);
  for (std::string l; std::getline(ss, l);) lines.push_back(l);
  return lines;
}

std::string join_lines(const std::vector<std::string>& lines) {
  std::string s;
  for (const auto& l : lines) s += l + "\n";
  return s;
}

// One to three mutations of `text`.
std::string mutate(std::string text, Rng& rng) {
  const int count = 1 + int(pick(rng, 3));
  for (int m = 0; m < count; ++m) {
    std::vector<std::string> lines = split_lines(text);
    if (lines.empty()) lines.push_back("");
    const size_t at = pick(rng, lines.size());
    switch (pick(rng, 8)) {
      case 0:  // a byte flipped to anything, structure characters included
        if (!text.empty()) {
          static const char special[] = "[]\"'=#\n\\{},.";
          text[pick(rng, text.size())] =
              pick(rng, 2) ? special[pick(rng, sizeof(special) - 1)] : char(pick(rng, 256));
        }
        continue;
      case 1:  // a line dropped
        lines.erase(lines.begin() + long(at));
        break;
      case 2:  // a line doubled (duplicate keys, duplicate tables)
        lines.insert(lines.begin() + long(at), lines[at]);
        break;
      case 3:  // cut short
        text.resize(pick(rng, text.size() + 1));
        continue;
      case 4:  // a key renamed
        if (auto eq = lines[at].find(" ="); eq != std::string::npos) lines[at].insert(eq, "x");
        break;
      case 5:  // a table header mangled or repeated
        lines.insert(lines.begin() + long(at), pick(rng, 2) ? "[sph]" : "[atom.extra]");
        break;
      default: {  // a value replaced by a hostile one
        std::vector<size_t> keys;
        for (size_t i = 0; i < lines.size(); ++i)
          if (lines[i].find(" = ") != std::string::npos && lines[i][0] != '#') keys.push_back(i);
        if (keys.empty()) break;
        std::string& l = lines[keys[pick(rng, keys.size())]];
        l = l.substr(0, l.find(" = ")) + " = " +
            hostile_values()[pick(rng, hostile_values().size())];
      }
    }
    text = join_lines(lines);
  }
  return text;
}

// Everything a command does with a scene before its kernels run: the file's parameters, the
// type's kernels and check inputs, and the domain's own cross-parameter validation.
void use_scene(const scene::ParamSet& p, const std::string& type_name) {
  const scene::SceneType& type = scene::find_scene_type(type_name);
  (void)type.kernels(p);
  (void)type.check_inputs(p);
  if (type_name == "sph") (void)sph::scene_from_params(p);
  if (type_name == "atom" || type_name == "atom-volume") {
    (void)atom::scatter_params_of(p);
    (void)atom::scene_options_of(p);
  }
}

struct Tally {
  int loaded = 0, refused = 0;
};

// Runs `step`; a masav::Error with a message is a refusal, anything else fails the test.
template <class F>
void expect_clean(Tally& t, const std::string& what, F&& step) {
  try {
    step();
    ++t.loaded;
  } catch (const Error& e) {
    ++t.refused;
    INFO(what);
    CHECK(std::string(e.what()).size() > 10);
  } catch (const std::exception& e) {
    FAIL_CHECK(what << ": not a masav::Error: " << e.what());
  }
}

int mutants_wanted() {
  const char* env = std::getenv("MASAV_FUZZ_MUTANTS");
  return env ? std::max(1, std::atoi(env)) : 400;
}

}  // namespace

TEST_CASE("scene fuzz: mutated scene files load or fail with a message") {
  const auto scenes = shipped_scenes();
  REQUIRE(scenes.size() >= 10);
  Rng rng(20261126);
  Tally t;
  const int n = mutants_wanted();
  for (int i = 0; i < n; ++i) {
    const auto& [name, text] = scenes[size_t(i) % scenes.size()];
    const std::string mutant = mutate(text, rng);
    expect_clean(t, fmt::format("mutant {} of {}:\n{}", i, name, mutant), [&] {
      const scene::SceneFile f = scene::parse_scene(mutant, name);
      use_scene(f.params, f.type);
    });
  }
  MESSAGE(fmt::format("{} mutants: {} loaded, {} refused with a message", n, t.loaded, t.refused));
  CHECK(t.loaded > 0);  // the mutants are not all broken beyond parsing
  CHECK(t.refused > 0);
}

TEST_CASE("scene fuzz: --set overrides with hostile values apply or fail with a message") {
  const auto scenes = shipped_scenes();
  Rng rng(7);
  Tally t;
  const int n = mutants_wanted();
  for (int i = 0; i < n; ++i) {
    const auto& [name, text] = scenes[size_t(i) % scenes.size()];
    scene::SceneFile f = scene::parse_scene(text, name);
    // A real key most of the time, sometimes a mangled one.
    std::vector<std::string> paths;
    for (const auto* table : f.params.tables())
      for (const auto& spec : table->params()) paths.push_back(table->name() + "." + spec.key);
    std::string path = paths[pick(rng, paths.size())];
    if (pick(rng, 8) == 0) path.insert(pick(rng, path.size() + 1), pick(rng, 2) ? "." : "x");
    std::string value = hostile_values()[pick(rng, hostile_values().size())];
    if (value.size() > 1 && value.front() == '"' && pick(rng, 2))
      value = value.substr(1, value.size() - 2);
    expect_clean(t, fmt::format("{}: --set {}={}", name, path, value), [&] {
      f.params.set_from_string(path, value);
      use_scene(f.params, f.type);
    });
  }
  MESSAGE(
      fmt::format("{} overrides: {} applied, {} refused with a message", n, t.loaded, t.refused));
  CHECK(t.loaded > 0);
  CHECK(t.refused > 0);
}
