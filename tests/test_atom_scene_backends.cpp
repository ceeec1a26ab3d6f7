// The atom-volume scene on every backend: the same stages run as on the CPU reference, the
// lit cloud and the raymarched image agree with it, and the scene's cross-check (every atom
// kernel against the reference) passes.
#include <doctest/doctest.h>

#include <cstdlib>
#include <filesystem>

#include "engine/scene/scene.h"
#include "engine/util/error_metrics.h"
#include "engine/verify/cross_check.h"
#include "registry/check_catalog.h"
#include "registry/scene_catalog.h"
#include "tests/backend_fixture.h"

using namespace masav;

TEST_CASE("the atom-volume scene runs the same stages on every backend and cross-checks") {
  namespace fs = std::filesystem;
  const fs::path cache = fs::temp_directory_path() / "masav_atom_backends_cache";
  const scene::SceneHost host{.cache_dir = cache.string()};
  const auto& type = scene::find_scene_type("atom-volume");
  scene::ParamSet p = scene::default_params(type);
  p.set("atom.count", int64_t(4096));
  p.set("nebula.density_dims", int64_t(16));
  p.set("scatter.rows", int64_t(120));
  p.set("scatter.tau_step", 0.05);
  p.set("scatter.photons", int64_t(128));
  p.set("volume.dims", int64_t(16));
  p.set("render.width", int64_t(32));
  p.set("render.height", int64_t(24));
  p.set("verify.max_points", int64_t(2048));
  p.set("camera.distance", 0.9);
  auto s = type.create(test::backend(), p, host);
  auto r = type.create(test::reference(), p, host);
  scene::FrameClock clock;
  for (const char* view : {"front", "front", "top"}) {
    s->set("camera.view", std::string(view));
    r->set("camera.view", std::string(view));
    const scene::UpdateReport a = s->update(clock, true);
    const scene::UpdateReport b = r->update(clock, true);
    CHECK(a.ran == b.ran);
    CHECK(a.skipped == b.skipped);
  }
  CHECK(s->graph().counters("viewer").runs == 2);
  CHECK(s->graph().counters("illuminate").runs == 1);
  // The lit cloud: the same positions (fp32 trigonometry) and light (fp32 path integrals);
  // tolerances as in tests/test_nebula.cpp, relative to 1e-6 of the largest light.
  const scene::SceneView sv = s->view(), rv = r->view();
  REQUIRE(sv.background.has_value());
  REQUIRE(rv.background.has_value());
  // The image layer's real4 pixels, as the backend stores them (fp32 or fp64).
  auto image = [](Backend& b, const scene::ImageLayer& img) {
    const size_t n = 4 * size_t(img.width) * img.height;
    std::vector<double> v(n);
    if (b.real_bytes() == 8) {
      b.download_bytes(*img.pixels, v.data(), 8 * n, 0);
    } else {
      std::vector<float> f(n);
      b.download_bytes(*img.pixels, f.data(), 4 * n, 0);
      v.assign(f.begin(), f.end());
    }
    return v;
  };
  const std::vector<double> got = image(test::backend(), *sv.background),
                            want = image(test::reference(), *rv.background);
  // The chain from fp32 positions to voxel counts moves a few points across cell faces: the
  // image agrees in the mean, not bit for bit.
  const ErrorStats e = compare(got, want, 1e-3);
  CAPTURE(describe(e));
  CHECK(e.rel_l2 < 2e-2);
  double lit = 0;
  for (size_t i = 3; i < want.size(); i += 4) lit += want[i] > 0.02;
  MESSAGE("pixels with alpha > 0.02: " << lit << " of " << want.size() / 4);
  CHECK(lit > 0.05 * double(want.size() / 4));  // the cloud covers part of the frame
  fs::remove_all(cache);

  const verify::CrossCheckReport report =
      verify::cross_check_scene(test::backend(), test::reference(), p);
  INFO(verify::format_report(report));
  CHECK(report.pass());
  CHECK(report.rows.size() == 12);
}
