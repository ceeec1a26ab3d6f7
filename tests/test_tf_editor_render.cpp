// The demo's transfer function editor, from its screenshots: with MASAV_TF_EDITOR_SHOTS set, the
// "tf editor demo screenshots" case inspects what `masav demo --script
// tests/data/tf_editor_demo_script.txt` wrote under xvfb-run (ctest cli.demo_tf_editor).
#include <doctest/doctest.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

#include "render/png.h"

using namespace masav;

namespace {

struct Counts {
  size_t lit = 0;         // coloured: brighter than the background, not the grey box lines
  size_t red = 0;         // lit, red well above green and blue
  size_t blue_green = 0;  // lit, green or blue well above red
  size_t pure_red = 0;    // red with almost no green and blue (not the panel's red-orange text)
};

Counts count(const render::Rgba8Image& img, uint32_t x0, uint32_t x1, uint32_t y0, uint32_t y1) {
  Counts c;
  for (uint32_t y = y0; y < y1; ++y)
    for (uint32_t x = x0; x < x1; ++x) {
      const uint8_t* p = &img.pixels[4 * (size_t(y) * img.width + x)];
      const int r = p[0], g = p[1], b = p[2];
      const int hi = std::max({r, g, b}), lo = std::min({r, g, b});
      if (hi <= 40 || hi - lo <= 24) continue;
      ++c.lit;
      c.pure_red += r > 100 && g < 16 && b < 16;
      c.red += r > 2 * std::max(g, b) + 20;
      c.blue_green += std::max(g, b) > r + 40;
    }
  return c;
}

int max_channel_difference(const render::Rgba8Image& a, const render::Rgba8Image& b) {
  int d = 0;
  for (size_t i = 0; i < a.pixels.size(); ++i)
    d = std::max(d, std::abs(int(a.pixels[i]) - int(b.pixels[i])));
  return d;
}

// The panel's left edge (the scene viewport's width) from the layout written beside a
// screenshot ("panel x y w h").
uint32_t panel_x(const std::string& layout_file) {
  std::ifstream f(layout_file);
  std::string key;
  uint32_t x = 0, y = 0, w = 0, h = 0;
  while (f >> key) {
    if (key == "expanded") {
      f >> x;
      continue;
    }
    f >> x >> y >> w >> h;
    if (key == "panel") return x;
  }
  return 0;
}

}  // namespace

TEST_CASE("tf editor demo screenshots" *
          doctest::skip(std::getenv("MASAV_TF_EDITOR_SHOTS") == nullptr)) {
  const std::string dir = std::getenv("MASAV_TF_EDITOR_SHOTS");
  const render::Rgba8Image def = render::read_png(dir + "/default.png");
  const render::Rgba8Image file = render::read_png(dir + "/red_file.png");
  const render::Rgba8Image red = render::read_png(dir + "/red.png");
  const render::Rgba8Image panel = render::read_png(dir + "/panel.png");
  REQUIRE(red.pixels.size() == def.pixels.size());
  REQUIRE(file.pixels.size() == red.pixels.size());
  // The middle of the scene (the panel is off): the volume, not the axes' colours at a corner.
  auto middle = [](const render::Rgba8Image& img) {
    return count(img, img.width / 4, img.width * 3 / 4, img.height / 4, img.height * 3 / 4);
  };
  const Counts d = middle(def), r = middle(red);
  MESSAGE("lit pixels: default " << d.lit << " (" << d.blue_green << " blue or green), red ramp "
                                 << r.lit << " (" << r.red << " red, " << r.blue_green
                                 << " blue or green)");
  // The default function shows its blue and green; the red ramp shows the volume in red only.
  CHECK(d.blue_green > d.lit / 4);
  CHECK(r.lit > red.width * red.height / 50);
  CHECK(r.red > r.lit * 9 / 10);
  CHECK(r.blue_green == 0);
  // The points edited in (the inline key) render as the same points from a `--tf` file do.
  CHECK(max_channel_difference(red, file) <= 1);
  // ...and as `masav run` renders them once, in the scene's viewport (left of the panel's strip).
  if (const char* run_png = std::getenv("MASAV_TF_EDITOR_RUN")) {
    const render::Rgba8Image run = render::read_png(run_png);
    const uint32_t scene_w = panel_x(dir + "/red.png.layout");
    REQUIRE(run.width == scene_w);
    REQUIRE(run.height == red.height);
    int d = 0;
    for (uint32_t y = 0; y < run.height; ++y)
      for (uint32_t x = 0; x < run.width; ++x)
        for (int k = 0; k < 3; ++k)
          d = std::max(d, std::abs(int(run.pixels[4 * (size_t(y) * run.width + x) + k]) -
                                   int(red.pixels[4 * (size_t(y) * red.width + x) + k])));
    CHECK(d <= 1);
  }
  // The panel holds the editor: its preview strip of the red ramp is the only pure red there.
  const uint32_t x0 = panel_x(dir + "/panel.png.layout");
  REQUIRE(x0 > 0);
  REQUIRE(x0 < panel.width);
  const Counts p = count(panel, x0, panel.width, 0, panel.height);
  MESSAGE("panel: " << p.pure_red << " pure red pixels from x = " << x0);
  CHECK(p.pure_red > 500);
  // The saved scene keeps the edited points inline, the file key cleared.
  std::ifstream saved(dir + "/out/demo/scene_0001.toml");
  std::stringstream text;
  text << saved.rdbuf();
  CHECK(text.str().find("transfer = \"0 0 0 0 0; 1 1 0 0 1\"") != std::string::npos);
  CHECK(text.str().find("transfer_file = \"\"") != std::string::npos);
}
