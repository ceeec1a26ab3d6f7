// The `volume` scene (a volume file raymarched; what the demo's "Open" shows) on the CPU
// reference: it reads its file when created, so a file `masav volume` refuses refuses the scene
// with the same message; its stages; a new path reloads; the [source] text keys are checked.
#include <doctest/doctest.h>

#include <fstream>
#include <string>
#include <vector>

#include "engine/core/error.h"
#include "engine/cpu/cpu_backend.h"
#include "engine/volume/volume_file.h"
#include "engine/volume/volume_scene.h"
#include "registry/scene_catalog.h"
#include "temp_dir.h"

using namespace masav;

namespace {

void write_ramp(const std::string& path, size_t bytes) {
  std::vector<char> v(bytes);
  for (size_t i = 0; i < bytes; ++i) v[i] = char(i % 200);
  std::ofstream(path, std::ios::binary).write(v.data(), std::streamsize(v.size()));
}

scene::ParamSet volume_params(const volume::VolumeFileOptions& o) {
  scene::ParamSet p = scene::default_params(scene::find_scene_type("volume"));
  volume::set_volume_file_options(p, o);
  p.set("render.width", int64_t(48));
  p.set("render.height", int64_t(32));
  return p;
}

// What the loader of `masav volume` says about these options ("" if it reads the file).
std::string cli_refusal(const volume::VolumeFileOptions& o) {
  try {
    (void)volume::load_volume_file(o);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("volume scene: a raw file raymarched; the stages; a new path reloads") {
  test::TempDir t("masav_volume_scene");
  write_ramp(t.file("a.raw"), 8 * 6 * 4);
  write_ramp(t.file("b.raw"), 4 * 4 * 4);
  cpu::CpuBackend cpu(2);
  const scene::SceneType& type = scene::find_scene_type("volume");
  auto s = type.create(cpu, volume_params({t.file("a.raw"), {8, 6, 4}, "uint8"}));
  scene::FrameClock clock;
  const scene::UpdateReport r = s->update(clock);
  CHECK(r.ran.size() == 4);  // load, transfer, bricks, raymarch
  CHECK(s->title() == "volume a.raw: 8x6x4 values in [0, 191]");
  const scene::SceneView v = s->view();
  REQUIRE(v.background);
  CHECK(v.background->width == 48);
  CHECK(v.background->key->lo == 0.0f);
  CHECK(v.background->key->hi == 191.0f);
  CHECK(v.box.hi.x - v.box.lo.x == doctest::Approx(8.0));
  // The camera moves: only the raymarch.
  s->set("camera.yaw_deg", 30.0);
  CHECK(s->update(clock).ran == std::vector<std::string>{"raymarch"});
  // Another file: read again, and everything after it.
  s->set("source.path", t.file("b.raw"));
  s->set("source.dims", std::string("4,4,4"));
  CHECK(s->update(clock).ran == std::vector<std::string>{"load", "bricks", "raymarch"});
  CHECK(s->title() == "volume b.raw: 4x4x4 values in [0, 63]");
}

TEST_CASE("volume scene: refused files and options read as masav volume words them") {
  test::TempDir t("masav_volume_scene_bad");
  write_ramp(t.file("short.raw"), 100);
  write_ramp(t.file("a.nrrd"), 10);
  cpu::CpuBackend cpu(2);
  const scene::SceneType& type = scene::find_scene_type("volume");
  const std::vector<volume::VolumeFileOptions> bad = {
      {t.file("short.raw"), {8, 8, 8}, "uint8"},   // shorter than its dims
      {t.file("short.raw"), {8, 8}, "uint8"},      // two sizes
      {t.file("short.raw"), {8, 8, 8}, "uint12"},  // no such type
      {t.file("short.raw"), {8, 8, 8}, ""},        // raw without a type
      {t.file("a.nrrd"), {8, 8, 8}, ""},           // a raw option for an NRRD
      {t.file("missing.vti"), {}, ""},             // no file
  };
  for (const volume::VolumeFileOptions& o : bad) {
    CAPTURE(o.file);
    const std::string cli = cli_refusal(o);
    REQUIRE(!cli.empty());
    std::string scene_message;
    try {
      (void)type.create(cpu, volume_params(o));
    } catch (const Error& e) {
      scene_message = e.what();
    }
    CHECK(scene_message == cli);
  }
  // The [source] keys are text; a size that is not a number names the key.
  scene::ParamSet p = volume_params({t.file("short.raw"), {}, "uint8"});
  p.set("source.dims", std::string("8,x,8"));
  CHECK_THROWS_WITH_AS((void)type.create(cpu, p), doctest::Contains("invalid source.dims = 8,x,8"),
                       Error);
  p.set("source.dims", std::string("8,8,8"));
  p.set("source.path", std::string(""));
  CHECK_THROWS_WITH_AS((void)type.create(cpu, p), doctest::Contains("source.path"), Error);
}
