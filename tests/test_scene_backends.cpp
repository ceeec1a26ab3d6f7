// The particle scene on every backend: the same stages run and are skipped as on the CPU
// reference, and the scene's cross-check against the reference passes.
#include <doctest/doctest.h>

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
