// The particle scene on every backend: the same stages run and are skipped as on the CPU
// reference, and the scene's cross-check against the reference passes.
#include <doctest/doctest.h>

#include <set>
#include <string>
#include <vector>

#include "engine/scene/scene.h"
#include "engine/verify/cross_check.h"
#include "registry/check_catalog.h"
#include "registry/scene_catalog.h"
#include "tests/backend_fixture.h"

using namespace masav;

TEST_CASE("the particle scene's stages run the same on every backend and cross-check") {
  scene::ParamSet p = scene::default_params(scene::find_scene_type("particles"));
  p.set("particles.count", int64_t(4096));
  p.set("particles.grid_cells", int64_t(12));
  p.set("render.width", int64_t(32));
  p.set("render.height", int64_t(32));
  const auto& type = scene::find_scene_type("particles");
  auto s = type.create(test::backend(), p);
  auto r = type.create(test::reference(), p);
  scene::FrameClock clock;
  for (double t : {0.0, 0.0, 0.25, 0.5}) {
    clock.time_s = t;
    const scene::UpdateReport a = s->update(clock, true);
    const scene::UpdateReport b = r->update(clock, true);
    CHECK(a.ran == b.ran);
    CHECK(a.skipped == b.skipped);
  }
  CHECK(s->graph().counters("drift_points").runs == 3);
  CHECK(s->graph().counters("stars").runs == 1);
  CHECK(s->graph().counters("stars").skips == 3);

  const verify::CrossCheckReport report =
      verify::cross_check_scene(test::backend(), test::reference(), p);
  INFO(verify::format_report(report));
  CHECK(report.pass());
  CHECK(report.rows.size() == 7);
}

// A kernel no shipped scene runs yet (a building block of a later pipeline) still has its
// built-in cross-check exercised here: it passes against the reference and catches a fault.
TEST_CASE("the built-in checks of kernels no scene runs pass and catch an injected fault") {
  std::set<KernelId> used;
  for (const auto& type : scene::scene_types())
    for (KernelId k : type.kernels(scene::default_params(type))) used.insert(k);
  scene::CheckInputs in;
  in.points = 5000;
  in.seed = 17;
  in.grid = make_grid_params({0, 0, 0}, 1.0f / 16, {16, 16, 16}, in.points);
  for (KernelId k : kAllKernels) {
    if (used.count(k)) continue;
    const std::vector<std::string> names = {std::string(kernel_name(k))};
    CAPTURE(names[0]);
    const verify::CrossCheckReport ok =
        verify::cross_check(test::backend(), test::reference(), names, in);
    INFO(verify::format_report(ok));
    CHECK(ok.pass());
    test::backend().inject_fault(k);
    const verify::CrossCheckReport bad =
        verify::cross_check(test::backend(), test::reference(), names, in);
    test::backend().inject_fault(std::nullopt);
    CHECK(!bad.pass());
  }
}
