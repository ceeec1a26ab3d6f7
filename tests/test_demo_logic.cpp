// The desktop demo's arithmetic, without a window: the layout of the scene viewport beside the
// panel, the window fitted to a screen, the steps per frame for a simulated-time rate, and the
// preview level of progressive volume rendering.
#include <doctest/doctest.h>

#include "app/demo/demo_layout.h"
#include "app/demo/idle_wait.h"
#include "app/demo/progressive.h"
#include "app/demo/sim_rate.h"
#include "registry/scene_file.h"

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

TEST_CASE("progressive rendering: full resolution when still, the level from the frame time") {
  LevelInputs in;
  in.max_level = 3;
  in.budget_ms = 50;
  in.first_level = 2;
  // Still: the full image, whatever was measured.
  in.level = 3, in.frame_ms = 30, in.raymarch_ms = 20;
  CHECK(next_preview_level(in) == 0);
  in.moving = true;
  // Nothing measured yet (a first moving frame): the level given for it.
  in.frame_ms = 0;
  CHECK(next_preview_level(in) == 2);
  in.frame_ms = 30, in.raymarch_ms = 0;  // no raymarch ran in the last frame
  CHECK(next_preview_level(in) == 2);
  // A full frame of 1000 ms, 960 of them raymarching: 40 + 960/4^L ms at level L, so level 2
  // (100 ms) is over the budget and level 3 (55 ms) too: the coarsest.
  in.level = 0, in.frame_ms = 1000, in.raymarch_ms = 960;
  CHECK(next_preview_level(in) == 3);
  // 10 ms besides a 160 ms full raymarch: level 1 takes 50 ms (at the budget), level 2 20 ms.
  in.frame_ms = 170, in.raymarch_ms = 160;
  CHECK(next_preview_level(in) == 1);
  // From level 2, a finer level needs a quarter of the budget to spare (37.5 ms): at 20 ms of
  // raymarch level 1 would take 10 + 80 ms; at 8 ms, 10 + 32 = 42 ms (within the budget but not
  // under the bar), so the level stays; at 6 ms, 10 + 24 = 34 ms, so it drops to 1.
  in.level = 2, in.frame_ms = 30, in.raymarch_ms = 20;
  CHECK(next_preview_level(in) == 2);
  in.frame_ms = 18, in.raymarch_ms = 8;
  CHECK(next_preview_level(in) == 2);
  in.frame_ms = 16, in.raymarch_ms = 6;
  CHECK(next_preview_level(in) == 1);
  // A level over the budget goes coarser at once.
  in.level = 1, in.frame_ms = 90, in.raymarch_ms = 80;  // 10 + 20 at level 2
  CHECK(next_preview_level(in) == 2);
  // A fast device stays at full resolution while moving.
  in.level = 0, in.frame_ms = 12, in.raymarch_ms = 5;
  CHECK(next_preview_level(in) == 0);
  // A scene without levels.
  in.max_level = 0;
  CHECK(next_preview_level(in) == 0);
  // The first moving level by device class, the script's words, the overlay's words.
  CHECK(first_preview_level("CPU device", 3) == 3);
  CHECK(first_preview_level("GPU", 3) == 0);
  CHECK(progressive_mode_from_word("auto")->enabled);
  CHECK(progressive_mode_from_word("auto")->fixed_level == 0);
  CHECK_FALSE(progressive_mode_from_word("off")->enabled);
  CHECK(progressive_mode_from_word("2")->fixed_level == 2);
  CHECK_FALSE(progressive_mode_from_word("0"));
  CHECK(progressive_mode_from_word("4")->fixed_level == 4);
  CHECK_FALSE(progressive_mode_from_word("5"));
  CHECK_FALSE(progressive_mode_from_word("fast"));
  CHECK(preview_label(0) == "volume: full resolution");
  CHECK(preview_label(2) == "volume: 1/4 resolution (moving)");
}

TEST_CASE("the demo waits for input only when nothing has changed for a few frames") {
  IdleInputs in;
  CHECK(idle_wait_seconds(in) == 0);  // just started
  in.quiet_frames = kIdleFramesBeforeWait - 1;
  CHECK(idle_wait_seconds(in) == 0);
  in.quiet_frames = kIdleFramesBeforeWait;
  CHECK(idle_wait_seconds(in) == kIdleWaitSeconds);
  CHECK(kIdleWaitSeconds <= 0.25);  // a tooltip or a blinking cursor still moves
  // What must keep drawing every frame.
  for (int what = 0; what < 3; ++what) {
    IdleInputs busy = in;
    (what == 0 ? busy.scripted : what == 1 ? busy.recording : busy.actions_queued) = true;
    CHECK(idle_wait_seconds(busy) == 0);
  }
}

TEST_CASE("demo: an SPH scene's particle count is lowered on a CPU device only when not given") {
  // The scene's default count is lowered to the device class's start count...
  CHECK(demo_particle_count(32768, false, 1024) == 1024);
  // ... a count the scene file or --set gave is kept, however large ...
  CHECK(demo_particle_count(4096, true, 1024) == 4096);
  // ... and a count that fits, or a GPU's (no limit), is never changed.
  CHECK(demo_particle_count(800, false, 1024) == 800);
  CHECK(demo_particle_count(32768, false, 0) == 32768);
  // "Given" is what the demo reads from the scene: a version above 0 once a file or --set set it.
  masav::scene::SceneFile f = masav::scene::default_scene("sph");
  CHECK(f.params.version("sph.count") == 0);
  f.params.set_from_string("sph.count", "4096");
  CHECK(f.params.version("sph.count") != 0);
  const masav::scene::SceneFile from_file =
      masav::scene::parse_scene("[scene]\ntype = \"sph\"\n[sph]\ncount = 2000\n", "<text>");
  CHECK(from_file.params.version("sph.count") != 0);
}
