// The tuning options (engine/core/tuning.h): every key takes its documented values, refuses
// anything else naming the key and what is allowed, and reaches the backend it tunes; a CPU
// backend created with options keeps them (the cross-check's reference gets the same).
#include <doctest/doctest.h>

#include <string>

#include "engine/core/error.h"
#include "engine/core/tuning.h"
#include "registry/backends.h"

using namespace masav;

namespace {

// A value each key accepts other than auto, as its `values` list spells it.
std::string accepted_value(const TuningKey& k) {
  const std::string values(k.values);
  if (values.find("whole number") != std::string::npos || values.find(" to ") != std::string::npos)
    return "1";
  const size_t start = values.rfind("auto, ", 0) == 0 ? 6 : 0;
  const std::string rest = values.substr(start);
  const size_t end = rest.find_first_of(", ");
  return rest.substr(0, end);
}

}  // namespace

TEST_CASE("every tuning option takes its values and names itself when refusing one") {
  REQUIRE(tuning_keys().size() >= 10);
  for (const TuningKey& k : tuning_keys()) {
    const std::string key(k.key);
    CAPTURE(key);
    CHECK_FALSE(k.description.empty());
    CHECK_FALSE(k.automatic.empty());
    Tuning t;
    const std::string v = accepted_value(k);
    CAPTURE(v);
    set_tuning(t, key + "=" + v);
    CHECK(describe(t) == key + "=" + v);  // set, and only it
    if (std::string(k.values).rfind("auto", 0) == 0) {
      set_tuning(t, key + "=auto");
      CHECK(describe(t).empty());
    }
    for (const char* bad : {"", "nan", "inf", "-1", "-0", "18446744073709551616", "yes", "ON",
                            " on", "1x", "0"}) {
      CAPTURE(bad);
      const std::string want = "invalid " + key + " = " + bad;
      CHECK_THROWS_WITH_AS(set_tuning(t, key + "=" + bad), doctest::Contains(want.c_str()), Error);
    }
  }
  Tuning t;
  CHECK_THROWS_WITH_AS(set_tuning(t, "vulkan.replays=on"),
                       doctest::Contains("invalid key = vulkan.replays"), Error);
  CHECK_THROWS_WITH_AS(set_tuning(t, "replay"), doctest::Contains("key=value"), Error);
  CHECK(describe(Tuning{}).empty());
}

TEST_CASE("a backend keeps the tuning it was created with") {
  Tuning t;
  set_tuning(t, "cpu.threads=1");
  set_tuning(t, "sph.neighbor_state=off");
  set_tuning(t, "vulkan.replay=off");
  const auto b = create_backend("cpu", "", BackendRequest{.tuning = t});
  CHECK(b->caps().threads == 1);
  CHECK(describe(b->tuning()) == describe(t));
  CHECK(b->tuning().sph.neighbor_state == Choice::off);
}
