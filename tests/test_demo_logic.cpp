// The desktop demo's arithmetic, without a window: the layout of the scene viewport beside the
// panel, the window fitted to a screen, and the steps per frame for a simulated-time rate.
#include <doctest/doctest.h>

#include "app/demo/demo_layout.h"
#include "app/demo/sim_rate.h"

using namespace masav::app;

TEST_CASE("demo layout: the scene and the panel share the window without overlap") {
  for (uint32_t w : {480u, 800u, 1152u, 1920u, 3840u})
    for (bool expanded : {true, false})
      for (float scale : {1.0f, 1.5f, 2.0f}) {
        CAPTURE(w);
        CAPTURE(expanded);
        CAPTURE(scale);
        const DemoLayout l = make_layout(w, 600, expanded, scale);
        CHECK(l.scene_w + l.panel_w == w);  // side by side, nothing hidden
        CHECK(l.panel_x == l.scene_w);
        CHECK(l.scene_h == 600);
        CHECK(l.scene_w >= 16);
        if (expanded) {
          CHECK(l.panel_w >= std::min(300u, w - 16));  // room for the labels
          CHECK(double(l.panel_w) <= std::max(300.0, 0.45 * w) + 1);
        } else {
          CHECK(l.panel_w <= uint32_t(32 * scale));
        }
      }
  // Collapsing gives the scene the panel's width back.
  CHECK(make_layout(1152, 720, false, 1).scene_w > make_layout(1152, 720, true, 1).scene_w + 300);
}

TEST_CASE("demo window: 90% of the screen's work area, at least 960x600 where it fits") {
  uint32_t w = 0, h = 0;
  fit_window(1280, 800, w, h);
  CHECK(w == 1152);
  CHECK(h == 720);
  fit_window(3840, 2160, w, h);
  CHECK(w == 3456);
  CHECK(h == 1944);
  fit_window(1024, 640, w, h);  // 90% would be below the minimum
  CHECK(w == 960);
  CHECK(h == 600);
  fit_window(800, 500, w, h);  // a screen below the minimum: all of it
  CHECK(w == 800);
  CHECK(h == 500);
  fit_window(0, 0, w, h);  // no monitor reported
  CHECK(w == 960);
  CHECK(h == 600);
}

TEST_CASE("demo pacing: steps per frame for a simulated time per second") {
  // 0.25 s/s over a 40 ms frame at dt 0.8 ms: 12.5, so 13 steps.
  CHECK(steps_for_rate(0.25, 0.04, 8e-4, 0.5, 60, 1000) == 13);
  // The device's pace caps it: 60 ms of steps at 20 ms each.
  CHECK(steps_for_rate(0.25, 0.04, 1e-4, 20, 60, 1000) == 3);
  // At least one step, at most the schema's maximum.
  CHECK(steps_for_rate(1e-6, 0.01, 1e-3, 0.1, 60, 1000) == 1);
  CHECK(steps_for_rate(10, 1.0, 1e-6, 0, 60, 1000) == 1000);
  CHECK(steps_for_rate(1, 0.1, 1e-3, 200, 60, 1000) == 1);  // one step is over the budget
  // Nothing known yet: one step.
  CHECK(steps_for_rate(0.25, 0, 1e-3, 0, 60, 1000) == 1);
  CHECK(steps_for_rate(0.25, 0.04, 0, 0, 60, 1000) == 1);
}

TEST_CASE("demo pacing: defaults per device class and the achieved rate") {
  const SimRateDefaults cpu = sim_rate_defaults("cpu"), gpu = sim_rate_defaults("discrete");
  CHECK(cpu.seconds_per_second < gpu.seconds_per_second);
  CHECK(cpu.max_particles > 0);
  CHECK(gpu.max_particles == 0);  // a GPU keeps the scene's count
  RateMeter m;
  CHECK(m.rate() == 0);
  m.add(0.01, 0.1);
  CHECK(m.rate() == doctest::Approx(0.1));
  for (int i = 0; i < 50; ++i) m.add(0.05, 0.1);  // settles on the new rate
  CHECK(m.rate() == doctest::Approx(0.5).epsilon(0.01));
  m.add(0.0, 0.0);  // an empty frame changes nothing
  CHECK(m.rate() == doctest::Approx(0.5).epsilon(0.01));
  m.reset();
  CHECK(m.rate() == 0);
}
