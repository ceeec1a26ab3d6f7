// The atom scenes' colour scale where no scene file fixes it (nebula.exposure = 0: a custom
// state, or a state picked in the demo): the state's own full-colour light, measured from the
// front. It must land where the shipped scene files' exposures put each state (they were set
// from the same 90th percentile; a scale from the mean radius alone drew state 1 3.5x over full
// colour and state 10 at an eighth of it), and it must not move with the view or the backend.
#include <doctest/doctest.h>
#include <fmt/format.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>

#include "engine/scene/scene.h"
#include "registry/scene_catalog.h"
#include "registry/scene_file.h"
#include "tests/backend_fixture.h"

using namespace masav;

namespace {

// The colour map's top (cd/a0^2 at the scene's power): 1 / exposure.
double full_colour(scene::SceneInstance& s) {
  scene::FrameClock clock;
  s.update(clock);
  const scene::SceneView v = s.view();
  REQUIRE(v.points.has_value());
  return v.points->scalar_hi;
}

}  // namespace

TEST_CASE("atom exposure 0: the state's own scale, as the scene files set it, in every view") {
  namespace fs = std::filesystem;
  const fs::path cache = fs::temp_directory_path() / "masav_atom_exposure_cache";
  const scene::SceneHost host{.cache_dir = cache.string()};
  // States 1, 5 and 10 span the scene files' scales from 50 to 0.037 cd/a0^2.
  for (const char* state : {"state1", "state5", "state10"}) {
    CAPTURE(state);
    scene::SceneFile f = scene::load_scene_file(std::string(MASAV_SOURCE_DIR) +
                                                "/scenes/atom_" + state + ".toml");
    const double file_scale = 1.0 / f.params.get_real("nebula.exposure");
    f.params.set("nebula.exposure", 0.0);
    f.params.set("atom.count", int64_t(200000));
    f.params.set("verify.enabled", false);
    const auto& type = scene::find_scene_type("atom");
    auto s = type.create(test::backend(), f.params, host);
    auto r = type.create(test::reference(), f.params, host);
    const double own = full_colour(*s), on_reference = full_colour(*r);
    s->set("camera.view", std::string("top"));
    const double from_top = full_colour(*s);
    s->set("camera.view", std::string("orbit"));
    s->set("camera.yaw_deg", 123.0);
    const double orbiting = full_colour(*s);
    MESSAGE(fmt::format("{}: own scale {:.4g} cd/a0^2 (reference backend {:.4g}), scene file {:.4g}",
                        state, own, on_reference, file_scale));
    CHECK(own > file_scale / 1.1);
    CHECK(own < file_scale * 1.1);
    CHECK(from_top == own);
    CHECK(orbiting == own);
    CHECK(std::abs(own - on_reference) <= 1e-3 * on_reference);
    CHECK(s->graph().counters("illuminate").runs == 1);
  }
  fs::remove_all(cache);
}

// A scene file's exposure is its state's: the demo's state buttons switch atom.state, and state 1
// under state 8's exposure would be a white blob 80x over full colour. Another state takes its
// own scale; an exposure set while it shows applies to it.
TEST_CASE("atom exposure: a scene file's exposure stays with its state") {
  namespace fs = std::filesystem;
  const fs::path cache = fs::temp_directory_path() / "masav_atom_exposure_switch_cache";
  const scene::SceneHost host{.cache_dir = cache.string()};
  scene::SceneFile f =
      scene::load_scene_file(std::string(MASAV_SOURCE_DIR) + "/scenes/atom_state8.toml");
  f.params.set("atom.count", int64_t(20000));
  f.params.set("verify.enabled", false);
  const auto& type = scene::find_scene_type("atom");
  auto s = type.create(test::backend(), f.params, host);
  const double file_scale = 1.0 / f.params.get_real("nebula.exposure");
  CHECK(full_colour(*s) == doctest::Approx(file_scale).epsilon(1e-6));
  s->set("atom.state", std::string("state1"));
  scene::ParamSet own = f.params;
  own.set("atom.state", std::string("state1"));
  own.set("nebula.exposure", 0.0);
  auto state1 = type.create(test::backend(), own, host);
  const double state1_scale = full_colour(*state1);
  MESSAGE(fmt::format("state 8's file scale {:.4g} cd/a0^2; state 1's own {:.4g}", file_scale,
                      state1_scale));
  CHECK(state1_scale > 10 * file_scale);
  CHECK(full_colour(*s) == state1_scale);
  // Saved (the demo's "Save scene"), it is state 1 at its own scale, not at state 8's exposure.
  CHECK(s->saved_params().get_real("nebula.exposure") == 0.0);
  s->set("nebula.exposure", 0.5);  // set for state 1: it applies
  CHECK(full_colour(*s) == doctest::Approx(2.0).epsilon(1e-6));
  CHECK(s->saved_params().get_real("nebula.exposure") == 0.5);
  s->set("atom.state", std::string("state8"));  // and not to state 8 again
  CHECK(full_colour(*s) != doctest::Approx(2.0).epsilon(1e-3));
  fs::remove_all(cache);
}
