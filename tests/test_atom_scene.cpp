// The atom and atom-volume scenes' stage graphs on the CPU reference: what runs on a change of
// source power (only the rescale), of the viewpoint (viewer attenuation and what reads it), of
// the frame size; the scattering table from the disk cache on the second run; the volume stages
// never created by the `atom` scene; every shipped atom scene file parses; bad input.
#include <doctest/doctest.h>
#include <fmt/format.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <functional>

#include "engine/core/error.h"
#include "engine/cpu/cpu_backend.h"
#include "engine/scene/scene.h"
#include "registry/scene_catalog.h"
#include "registry/scene_file.h"

using namespace masav;
using namespace masav::scene;

namespace {

namespace fs = std::filesystem;

using Names = std::vector<std::string>;

// The first update's order among independent stages is the graph's business: compare as sets.
Names sorted(Names v) {
  std::sort(v.begin(), v.end());
  return v;
}

// A small cloud and table: the stages' logic, not their physics, is under test here.
ParamSet small_atom(const char* type) {
  ParamSet p = default_params(find_scene_type(type));
  p.set("atom.count", int64_t(3000));
  p.set("nebula.density_dims", int64_t(12));
  p.set("scatter.rows", int64_t(40));
  p.set("scatter.tau_step", 0.1);
  p.set("scatter.photons", int64_t(64));
  p.set("render.width", int64_t(48));
  p.set("render.height", int64_t(36));
  if (p.has_table("volume")) p.set("volume.dims", int64_t(12));
  return p;
}

// A fresh cache directory for the test's lifetime, passed to the scenes it creates.
struct TempCache {
  fs::path dir;
  explicit TempCache(const char* name) : dir(fs::temp_directory_path() / name) {
    fs::remove_all(dir);
  }
  ~TempCache() { fs::remove_all(dir); }
  scene::SceneHost host() const { return {.cache_dir = dir.string()}; }
};

}  // namespace

TEST_CASE("atom scene: power rescales, the view reruns only the attenuation, the table is cached") {
  TempCache cache("masav_atom_scene_test");
  cpu::CpuBackend cpu(2);
  const ParamSet p = small_atom("atom");
  auto s = find_scene_type("atom").create(cpu, p, cache.host());
  FrameClock clock;
  UpdateReport r = s->update(clock);
  CHECK(sorted(r.ran) ==
        sorted({"cloud", "density", "scatter_table", "illuminate", "viewer", "light"}));
  CHECK(r.cached.empty());  // a fresh cache: the table is computed (and stored)
  CHECK(s->update(clock).ran.empty());
  const float hi_250k = s->view().points->scalar_hi;

  // Phi: light is linear in it, so only the rescale runs; the colour map's top moves with it.
  s->graph().reset_counters();
  s->set("nebula.power_lm", 500000.0);
  CHECK(s->update(clock).ran == Names{"light"});
  CHECK(s->graph().counters("illuminate").runs == 0);
  CHECK(s->graph().counters("viewer").runs == 0);
  CHECK(s->view().points->scalar_hi == doctest::Approx(0.5 * hi_250k).epsilon(1e-6));

  // A new viewpoint: the viewer attenuation and the rescale, nothing before them.
  s->set("camera.view", std::string("top"));
  CHECK(s->update(clock).ran == Names{"viewer", "light"});
  s->set("camera.yaw_deg", 10.0);  // the orbit angles change the pose only in orbit view
  s->set("camera.view", std::string("orbit"));
  CHECK(s->update(clock).ran == Names{"viewer", "light"});
  // What only the renderer reads runs nothing.
  s->set("render.point_size", 5.0);
  s->set("render.colormap", std::string("grey"));
  CHECK(s->update(clock).ran.empty());
  // The optical depth: the lighting and everything after it, not the cloud or the table.
  s->set("nebula.tau_peak", 1.0);
  CHECK(s->update(clock).ran == Names{"illuminate", "viewer", "light"});
  // Another state: everything but the table.
  s->set("atom.state", std::string("state3"));
  CHECK(s->update(clock).ran == Names{"cloud", "density", "illuminate", "viewer", "light"});
  CHECK(s->graph().counters("scatter_table").runs == 0);

  // The `atom` scene has no volume stages at all: no buffers, no pipelines.
  for (const auto& c : s->graph().counters())
    for (const char* volume_stage : {"voxelize", "transfer", "bricks", "raymarch"})
      CHECK(c.name != volume_stage);
  CHECK_FALSE(s->view().background.has_value());

  // The next run of masav: the same table parameters load from the disk cache.
  auto again = find_scene_type("atom").create(cpu, p, cache.host());
  r = again->update(clock);
  CHECK(r.cached == Names{"scatter_table"});
  CHECK(again->graph().counters("scatter_table").cache_hits == 1);
}

TEST_CASE("atom-volume scene: the raymarch follows the view, power and frame size") {
  TempCache cache("masav_atom_volume_scene_test");
  cpu::CpuBackend cpu(2);
  auto s = find_scene_type("atom-volume").create(cpu, small_atom("atom-volume"), cache.host());
  FrameClock clock;
  UpdateReport r = s->update(clock);
  CHECK(sorted(r.ran) == sorted({"cloud", "density", "scatter_table", "illuminate", "viewer",
                                 "light", "voxelize", "transfer", "bricks", "raymarch"}));
  REQUIRE(s->view().background.has_value());
  CHECK(s->view().background->width == 48);
  CHECK_FALSE(s->view().points.has_value());  // show_particles = false
  // Phi: the rescale and the volume that shows the light; no lighting pass.
  s->set("nebula.power_lm", 100000.0);
  CHECK(s->update(clock).ran == Names{"light", "voxelize", "bricks", "raymarch"});
  // The view: the viewer attenuation and what reads the light, then the raymarch; the cloud,
  // its density, the table and the illumination stay.
  s->set("camera.view", std::string("left"));
  CHECK(s->update(clock).ran == Names{"viewer", "light", "voxelize", "bricks", "raymarch"});
  // The frame size and the raymarch step: the raymarch only.
  s->set("render.width", int64_t(40));
  s->set("volume.step_voxels", 1.0);
  CHECK(s->update(clock).ran == Names{"raymarch"});
  CHECK(s->view().background->width == 40);
  // The volume mix: the volume, not the lighting.
  s->set("volume.s", 0.3);
  CHECK(s->update(clock).ran == Names{"voxelize", "bricks", "raymarch"});
  // Particles over the volume: nothing to compute, the light is there already.
  s->set("volume.show_particles", true);
  CHECK(s->update(clock).ran.empty());
  CHECK(s->view().points.has_value());
  // A turning camera is a new view every frame.
  s->set("camera.view", std::string("orbit"));
  s->set("camera.orbit_speed_deg", 20.0);
  s->update(clock);
  clock.time_s = 0.5;
  CHECK(s->update(clock).ran == Names{"viewer", "light", "voxelize", "bricks", "raymarch"});
  CHECK(s->graph().counters("illuminate").runs == 1);
  CHECK(s->graph().counters("cloud").runs == 1);
}

TEST_CASE(
    "atom-volume scene: preview levels raymarch a smaller image, the light held; the full "
    "level is the one-shot image") {
  TempCache cache("masav_atom_volume_preview_test");
  cpu::CpuBackend cpu(2);
  ParamSet p = small_atom("atom-volume");
  p.set("camera.view", std::string("orbit"));
  p.set("camera.orbit_speed_deg", 20.0);
  auto s = find_scene_type("atom-volume").create(cpu, p, cache.host());
  FrameClock clock;
  s->update(clock);
  CHECK(s->max_preview_level() == kMaxPreviewLevel);
  auto image = [&](const SceneInstance& scene) {
    const SceneView v = scene.view();  // a value: the layer must outlive this call's temporary
    REQUIRE(v.background.has_value());
    const auto& bg = *v.background;
    std::vector<uint8_t> bytes(size_t(bg.width) * bg.height * 4 * cpu.real_bytes());
    cpu.download_bytes(*bg.pixels, bytes.data(), bytes.size(), 0);
    return bytes;
  };
  // A preview samples a voxel apart (the scene's step is 1/2 voxel): at level 1, the one-shot
  // image of a 24x18 frame at step 1 voxel.
  s->set_preview_level(1);
  CHECK(s->update(clock).ran == Names{"raymarch"});
  CHECK(s->view().background->width == 24);
  {
    ParamSet small = p;
    small.set("render.width", int64_t(24));
    small.set("render.height", int64_t(18));
    small.set("volume.step_voxels", 1.0);
    auto coarse = find_scene_type("atom-volume").create(cpu, small, cache.host());
    coarse->update(clock);
    CHECK(image(*s) == image(*coarse));
  }
  // A preview of the same view: the raymarch only, at a quarter of the 48x36 frame per axis.
  s->set_preview_level(2);
  CHECK_FALSE(s->changes_pending(clock));  // the preview level is not a change of the scene
  CHECK(s->update(clock).ran == Names{"raymarch"});
  CHECK(s->view().background->width == 12);
  CHECK(s->view().background->height == 9);
  // The orbit turns: a change; the preview raymarches the new view with the light it had.
  clock.time_s = 0.5;
  CHECK(s->changes_pending(clock));
  CHECK(s->update(clock).ran == Names{"raymarch"});
  // The full level relights for the current view and raymarches the whole frame...
  s->set_preview_level(0);
  CHECK(s->update(clock).ran == Names{"viewer", "light", "voxelize", "bricks", "raymarch"});
  CHECK(s->view().background->width == 48);
  CHECK_FALSE(s->changes_pending(clock));
  CHECK(s->update(clock).ran.empty());  // ...and then nothing runs while nothing changes
  // The same image as a scene rendered once at this time.
  auto once = find_scene_type("atom-volume").create(cpu, p, cache.host());
  once->update(clock);
  CHECK(image(*s) == image(*once));
  s->set_preview_level(9);
  CHECK(s->preview_level() == kMaxPreviewLevel);  // clamped to the scene's coarsest
}

TEST_CASE("every atom scene file parses, and atom parameters are checked") {
  for (int i = 1; i <= 10; ++i) {
    const SceneFile f =
        load_scene_file(fmt::format("{}/scenes/atom_state{}.toml", MASAV_SOURCE_DIR, i));
    CHECK(f.type == "atom");
    CHECK(f.params.get_text("atom.state") == fmt::format("state{}", i));
  }
  const SceneFile v = load_scene_file(std::string(MASAV_SOURCE_DIR) + "/scenes/atom_volume.toml");
  CHECK(v.type == "atom-volume");

  auto error_of = [](const std::function<void()>& fn) -> std::string {
    try {
      fn();
    } catch (const Error& e) {
      return e.what();
    }
    return "(no error)";
  };
  std::string e = error_of(
      [] { parse_scene("[scene]\ntype = \"atom\"\n[nebula]\npower_lm = 1e6\n", "a.toml"); });
  CHECK(e.find("nebula.power_lm") != std::string::npos);
  CHECK(e.find("50000") != std::string::npos);
  e = error_of(
      [] { parse_scene("[scene]\ntype = \"atom\"\n[atom]\nstate = \"state11\"\n", "a.toml"); });
  CHECK(e.find("atom.state") != std::string::npos);
  CHECK(e.find("state10") != std::string::npos);
  e = error_of([] { parse_scene("[scene]\ntype = \"atom\"\n[volume]\ndims = 8\n", "a.toml"); });
  CHECK(e.find("volume") != std::string::npos);  // atom has no [volume] table
  // A custom state that is no hydrogen state: named at scene creation.
  cpu::CpuBackend cpu(1);
  ParamSet p = small_atom("atom");
  p.set("atom.state", std::string("custom"));
  p.set("atom.n", int64_t(2));
  p.set("atom.l", int64_t(2));
  e = error_of([&] { find_scene_type("atom").create(cpu, p); });
  CHECK(e.find("l = 2") != std::string::npos);
  CHECK(e.find("[0, 1]") != std::string::npos);
  // ... and when set at run time, the old state stays.
  p.set("atom.l", int64_t(1));
  auto s = find_scene_type("atom").create(cpu, p);
  e = error_of([&] { s->set("atom.m", int64_t(-2)); });
  CHECK(e.find("m = -2") != std::string::npos);
  CHECK(s->params().get_int("atom.m") == 0);
}

TEST_CASE("atom scene title: the file's while its state is shown, the state's after a switch") {
  cpu::CpuBackend cpu(1);
  SceneFile f = load_scene_file(std::string(MASAV_SOURCE_DIR) + "/scenes/atom_state3.toml");
  auto s = find_scene_type("atom").create(cpu, f.params);
  CHECK(s->title() == "hydrogen state 3: n=2 l=1 m=0");
  CHECK(s->set("atom.state", std::string("state8")));
  CHECK(s->title() == "hydrogen state8: n=3 l=2 m=0 (complex)");
  CHECK(s->set("atom.state", std::string("state3")));  // back to the file's state: its title
  CHECK(s->title() == "hydrogen state 3: n=2 l=1 m=0");
  CHECK(s->set("atom.state", std::string("custom")));
  CHECK(s->set("atom.n", int64_t(4)));
  CHECK(s->set("atom.l", int64_t(3)));
  CHECK(s->title() == "hydrogen custom: n=4 l=3 m=0 (complex)");
  CHECK_FALSE(s->simulated_time_s().has_value());  // the atom follows the frame clock
}
