// The `sph` scene drawn headless on lavapipe (validation on): the cube drop renders non-blank,
// and after it has fallen and splashed the fluid is at the bottom of the box -- its centre of
// mass (read from the simulation's own buffers) and its pixels in the front view, where the
// initial cube sat above the box's middle. With MASAV_DEMO_SPH_SHOTS set, "demo sph screenshots"
// inspects what `masav demo --script` wrote for the SPH scene under xvfb-run.
#include <doctest/doctest.h>
#include <fmt/format.h>

#include <algorithm>
#include <cstdlib>
#include <glm/glm.hpp>
#include <string>

#include "engine/sph/sph_scene_type.h"
#include "engine/sph/sph_simulation.h"
#include "registry/scene_file.h"
#include "render/png.h"
#include "render/scene_player.h"
#include "tests/host_options.h"

using namespace masav;

namespace {

struct Image {
  uint32_t w = 0, h = 0;
  std::vector<uint8_t> px;
  int sum(uint32_t x, uint32_t y) const {
    const size_t i = 4 * (size_t(y) * w + x);
    return px[i] + px[i + 1] + px[i + 2];
  }
};

// Pixels brighter than the clear colour, in rows [y0, y1) and columns [0, x1).
struct LitStats {
  size_t count = 0;
  double mean_row = 0;
};
LitStats lit_pixels(const Image& f, uint32_t x1, uint32_t y0, uint32_t y1) {
  LitStats s;
  for (uint32_t y = y0; y < y1; ++y)
    for (uint32_t x = 0; x < x1; ++x)
      if (f.sum(x, y) > 90) ++s.count, s.mean_row += y;
  if (s.count) s.mean_row /= double(s.count);
  return s;
}

// Image row of a world point under the camera the renderer used (row 0 at the top).
double row_of(const render::Camera& c, glm::vec3 p, uint32_t h) {
  const glm::vec4 clip = c.view_proj * glm::vec4(p, 1.0f);
  return (clip.y / clip.w * 0.5 + 0.5) * double(h);
}

}  // namespace

TEST_CASE("the SPH cube drop renders and the fluid ends at the bottom of the box") {
  scene::SceneFile file = scene::load_scene_file(MASAV_SOURCE_DIR "/scenes/sph_water.toml");
  scene::ParamSet& p = file.params;
  p.set("sph.count", int64_t(600));
  p.set("sph.substeps", int64_t(60));
  p.set("render.width", int64_t(240));
  p.set("render.height", int64_t(180));
  p.set("render.overlay", false);
  p.set("render.show_box", false);
  p.set("render.show_axes", false);
  p.set("camera.view", std::string("front"));
  render::PlayerOptions po;
  po.backend = "vulkan";
  po.graphics = test::graphics_options();
  po.cache_dir = test::cache_dir();
  render::ScenePlayer player(file, po);
  auto frame = [&](uint64_t i) {
    player.clock().frame = i;
    player.update();
    render::FrameRequest req;
    req.readback = true;
    player.draw(req);
    return Image{player.renderer().width(), player.renderer().height(), player.renderer().pixels()};
  };
  const Image first = frame(0);
  const SphSimulation* sim = sph::simulation_of(player.scene());
  REQUIRE(sim != nullptr);
  const SphScene& sc = sim->scene();
  // Rows of the box's floor and of its mid-height in the front view.
  const render::Camera& cam = player.renderer().camera();
  const float cx = float(0.5 * (sc.box_min.x + sc.box_max.x));
  const float cz = float(0.5 * (sc.box_min.z + sc.box_max.z));
  const double floor_row = row_of(cam, {cx, float(sc.box_min.y), cz}, first.h);
  const double mid_row = row_of(cam, {cx, float(0.5 * (sc.box_min.y + sc.box_max.y)), cz}, first.h);
  REQUIRE(floor_row > mid_row);  // y up is up in the image
  const LitStats a = lit_pixels(first, first.w, 0, first.h);
  MESSAGE("initial: " << a.count << " lit pixels, mean row " << a.mean_row << " (mid " << mid_row
                      << ", floor " << floor_row << ")");
  CHECK(a.count > 400);         // not blank
  CHECK(a.mean_row < mid_row);  // the cube starts in the upper half

  // Let it fall (0.45 m: 0.3 s), splash and run out along the floor.
  uint64_t i = 1;
  while (sim->time() < 0.6 && i < 400) frame(i++);
  CHECK(sim->time() >= 0.6);
  const Image last = frame(i);
  const std::vector<Vec4d> pos = player.backend().download(sim->positions());
  double com_y = 0;
  for (const auto& q : pos) com_y += q.y;
  com_y /= double(pos.size());
  const double height = sc.box_max.y - sc.box_min.y;
  MESSAGE("after " << sim->steps() << " steps (t = " << sim->time()
                   << " s): centre of mass at y = " << com_y << " m of " << height);
  CHECK(com_y < sc.box_min.y + 0.25 * height);
  const LitStats b = lit_pixels(last, last.w, 0, last.h);
  const LitStats below = lit_pixels(last, last.w, uint32_t(mid_row), last.h);
  MESSAGE("final: " << b.count << " lit pixels, mean row " << b.mean_row << ", " << below.count
                    << " below the middle");
  CHECK(b.count > 400);
  CHECK(b.mean_row > mid_row);
  CHECK(double(below.count) > 0.85 * double(b.count));  // 94% measured: splashes fly higher
}

TEST_CASE("demo sph screenshots" * doctest::skip(std::getenv("MASAV_DEMO_SPH_SHOTS") == nullptr)) {
  // Written by tests/data/demo_sph_script.txt: a (the water falling for a while), b (rk4,
  // restarted and stepped once while paused), c (the same state in one colour), d (c as a fluid
  // surface).
  const std::string dir = std::getenv("MASAV_DEMO_SPH_SHOTS");
  auto load = [&](const char* name) {
    const render::Rgba8Image img = render::read_png(dir + "/" + name);
    return Image{img.width, img.height, img.pixels};
  };
  const Image a = load("a.png"), b = load("b.png"), c = load("c.png"), d = load("d.png");
  // The scene area: left of the panel, below the overlay.
  auto scene_area = [](const Image& f) { return lit_pixels(f, f.w / 2, f.h / 4, f.h); };
  const LitStats la = scene_area(a), lb = scene_area(b), lc = scene_area(c);
  MESSAGE("lit a " << la.count << " (row " << la.mean_row << "), b " << lb.count << " (row "
                   << lb.mean_row << "), c " << lc.count);
  CHECK(la.count > 300);
  CHECK(lb.count > 300);
  CHECK(lc.count > 300);
  // The restart put the cube back at the top: b's fluid sits higher than a's.
  CHECK(lb.mean_row + 5 < la.mean_row);
  // One colour (the map's middle, green) instead of speed (slow: blue): the same particles,
  // other colours.
  size_t differ = 0;
  for (uint32_t y = b.h / 4; y < b.h; ++y)
    for (uint32_t x = 0; x < b.w / 2; ++x) {
      const size_t i = 4 * (size_t(y) * b.w + x);
      int d = 0;
      for (int k = 0; k < 3; ++k) d = std::max(d, std::abs(int(b.px[i + k]) - int(c.px[i + k])));
      differ += d > 60;
    }
  MESSAGE(differ << " pixels recoloured");
  CHECK(differ > 300);
  // The colour bar at the bottom left of the demo's frame: the thesis map's pure red top and
  // blue bottom (b's fluid is back at the top of the box, away from the bar).
  size_t red = 0, blue = 0;
  for (uint32_t y = b.h / 2; y < b.h; ++y)
    for (uint32_t x = 0; x < 40; ++x) {
      const size_t i = 4 * (size_t(y) * b.w + x);
      red += b.px[i] > 200 && b.px[i + 1] < 90 && b.px[i + 2] < 90;
      blue += b.px[i + 2] > 200 && b.px[i] < 60 && b.px[i + 1] < 60;
    }
  MESSAGE("colour bar: " << red << " red, " << blue << " blue pixels");
  CHECK(red > 10);
  CHECK(blue > 10);
  // The fluid surface: drawn, and shaded unlike the spheres of the same state.
  const LitStats ld = scene_area(d);
  size_t reshaded = 0;
  for (uint32_t y = c.h / 4; y < c.h; ++y)
    for (uint32_t x = 0; x < c.w / 2; ++x) {
      const size_t i = 4 * (size_t(y) * c.w + x);
      int e = 0;
      for (int k = 0; k < 3; ++k) e = std::max(e, std::abs(int(c.px[i + k]) - int(d.px[i + k])));
      reshaded += e > 40;
    }
  MESSAGE("surface: lit " << ld.count << ", " << reshaded << " pixels differ from the spheres");
  CHECK(ld.count > 300);
  CHECK(reshaded > 200);
}

TEST_CASE("the SPH overlay shows the simulated time, the frame clock labelled apart") {
  scene::SceneFile file = scene::load_scene_file(MASAV_SOURCE_DIR "/scenes/sph_dambreak.toml");
  file.params.set("sph.count", int64_t(600));
  file.params.set("render.width", int64_t(160));
  file.params.set("render.height", int64_t(120));
  render::PlayerOptions po;
  po.backend = "cpu";
  po.graphics = test::graphics_options();
  po.cache_dir = test::cache_dir();
  render::ScenePlayer player(file, po);
  for (uint64_t i = 0; i <= 11; ++i) {
    player.clock().frame = i;
    player.clock().time_s = double(i) / file.params.get_real("run.fps");
    player.update();
  }
  const SphSimulation* sim = sph::simulation_of(player.scene());
  REQUIRE(sim != nullptr);
  const std::vector<std::string> lines = render::overlay_lines(player.overlay());
  REQUIRE(lines.size() > 1);
  CHECK(lines[0] == "masav: SPH dam break");
  const std::string want = fmt::format("frame 11  t = {:.4f} s simulated (frame clock {:.2f} s)",
                                       sim->time(), player.clock().time_s);
  CHECK(lines[1] == want);
  CHECK(sim->time() < player.clock().time_s);
  // The title follows a preset change.
  player.scene().set("sph.preset", std::string("water"));
  CHECK(render::overlay_lines(player.overlay())[0] == "masav: SPH water");
}

TEST_CASE("colour bar ticks are round values between the range's ends") {
  CHECK(render::nice_ticks(0, 0.3) == std::vector<double>{0, 0.1, 0.2, 0.30000000000000004});
  CHECK(render::nice_ticks(0, 2.45).size() == 5);  // 0, 0.5, ..., 2
  CHECK(render::nice_ticks(800, 1100) == std::vector<double>{800, 900, 1000, 1100});
  CHECK(render::tick_label(0.5, 0.5) == "0.5");
  CHECK(render::tick_label(1000, 100) == "1000");
  CHECK(render::tick_label(0.0002, 0.0001) == "0.0002");
  CHECK(render::nice_ticks(1, 1).size() == 1);  // an empty range: one tick, no division by 0
}

// The colour bar at the bottom left of an SPH frame: its gradient shows the colour map from the
// range's bottom to its top at the heights of its ticks, its title names the quantity and the
// unit, and its labels are the ticks' values -- found through the bar's layout, as drawn.
TEST_CASE("the colour bar shows the colour map, its tick labels and the quantity's unit") {
  scene::SceneFile file = scene::load_scene_file(MASAV_SOURCE_DIR "/scenes/sph_water.toml");
  file.params.set("sph.count", int64_t(600));
  file.params.set("render.width", int64_t(320));
  file.params.set("render.height", int64_t(240));
  file.params.set("camera.view", std::string("front"));
  render::PlayerOptions po;
  po.backend = "vulkan";
  po.graphics = test::graphics_options();
  po.cache_dir = test::cache_dir();
  render::ScenePlayer player(file, po);
  player.update();
  render::FrameRequest req;
  req.readback = true;
  player.draw(req);
  const Image img{player.renderer().width(), player.renderer().height(),
                  player.renderer().pixels()};
  const render::OverlayInfo o = player.overlay();
  REQUIRE(o.colour_bar.has_value());
  const render::ColourBar& bar = *o.colour_bar;
  CHECK(bar.title == "speed (m/s)");
  CHECK(bar.lo == 0.0f);
  CHECK(bar.hi > 1.0f);
  player.ui().make_current();
  const render::ColourBarLayout l = render::colour_bar_layout_in_frame(bar);
  REQUIRE(l.ticks.size() >= 3);
  CHECK(l.ticks.front().label == "0");
  CHECK(l.x0 >= 0);
  CHECK(l.y1 < float(img.h));
  CHECK(l.title_y > float(img.h) / 2);  // bottom left, clear of the overlay's text
  const render::ColormapTable thesis = render::colormap_table("thesis");
  for (const auto& t : l.ticks) {
    CAPTURE(t.label);
    CHECK(t.label == render::tick_label(t.value, l.ticks[1].value - l.ticks[0].value));
    CHECK(t.value >= bar.lo);
    CHECK(t.value <= bar.hi);
    // The gradient's colour at the tick's height is the colour map's at the tick's value.
    const uint32_t y = uint32_t(std::clamp(t.y, l.y0 + 2.0f, l.y1 - 2.0f));
    const uint32_t x = uint32_t(0.5f * (l.x0 + l.x1));
    const size_t i = 4 * (size_t(y) * img.w + x);
    const double v = bar.lo + (bar.hi - bar.lo) * (l.y1 - float(y)) / (l.y1 - l.y0);
    const Vec4f want = render::colour_at(bar, v);
    CHECK(std::abs(img.px[i] - 255.0 * want.x) < 16);
    CHECK(std::abs(img.px[i + 1] - 255.0 * want.y) < 16);
    CHECK(std::abs(img.px[i + 2] - 255.0 * want.z) < 16);
  }
  // The map's ends: blue at the bottom, red at the top.
  CHECK(render::colour_at(bar, bar.lo).z == doctest::Approx(thesis.front().z));
  CHECK(render::colour_at(bar, bar.hi).x == doctest::Approx(thesis.back().x));
  // The title is drawn: light text pixels in its line.
  size_t text = 0;
  for (uint32_t y = uint32_t(l.title_y); y < uint32_t(l.title_y) + 10; ++y)
    for (uint32_t x = uint32_t(l.title_x); x < uint32_t(l.title_x) + 80; ++x)
      text += img.sum(x, y) > 600;
  CHECK(text > 20);
}
