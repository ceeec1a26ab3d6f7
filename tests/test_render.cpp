// Rendering through Vulkan (lavapipe in CI): points land where the camera projects them, in the
// colour map's colours, depth-tested; the background image and the box are drawn; the copy path
// (CPU backend) and the shared-device path (Vulkan backend) give the same image; the particle
// scene renders non-blank, changing frames; PNGs round-trip. With MASAV_DEMO_SHOTS set, the
// "demo screenshots" case inspects what `masav demo --script` wrote under xvfb-run.
#define DOCTEST_CONFIG_IMPLEMENT
#include <doctest/doctest.h>
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>

#include "compute/device/vk_context.h"
#include "engine/core/error.h"
#include "engine/cpu/cpu_backend.h"
#include "engine/scene/scene.h"
#include "registry/backends.h"
#include "registry/scene_catalog.h"
#include "render/png.h"
#include "render/renderer.h"
#include "render/scene_player.h"
#include "tests/host_options.h"

using namespace masav;

namespace {

struct Rgb {
  int r, g, b;
};

struct Frame {
  uint32_t w = 0, h = 0;
  std::vector<uint8_t> px;
  Rgb at(int x, int y) const {
    const size_t i = 4 * (size_t(y) * w + size_t(x));
    return {px[i], px[i + 1], px[i + 2]};
  }
  // The brightest pixel (by r+g+b) within `radius` of (x, y).
  Rgb brightest(int x, int y, int radius) const {
    Rgb best{-1, -1, -1};
    for (int yy = std::max(0, y - radius); yy <= std::min(int(h) - 1, y + radius); ++yy)
      for (int xx = std::max(0, x - radius); xx <= std::min(int(w) - 1, x + radius); ++xx) {
        const Rgb c = at(xx, yy);
        if (c.r + c.g + c.b > best.r + best.g + best.b) best = c;
      }
    return best;
  }
  double mean() const {
    double s = 0;
    for (size_t i = 0; i < px.size(); i += 4) s += px[i] + px[i + 1] + px[i + 2];
    return s / (3.0 * w * h);
  }
};

// Fraction of pixels whose colour differs by more than `tol` in some channel.
double fraction_differing(const Frame& a, const Frame& b, int tol = 24) {
  REQUIRE(a.px.size() == b.px.size());
  size_t n = 0;
  for (size_t i = 0; i < a.px.size(); i += 4)
    for (int c = 0; c < 3; ++c)
      if (std::abs(int(a.px[i + c]) - int(b.px[i + c])) > tol) {
        ++n;
        break;
      }
  return double(n) / double(a.w * a.h);
}

// Not the clear colour (5, 5, 10) nor a faint star.
bool lit(const Rgb& c) {
  return c.r + c.g + c.b > 90;
}

scene::ParamSet plain_params(uint32_t w, uint32_t h) {
  scene::ParamSet p = scene::default_params(scene::find_scene_type("particles"));
  p.set("render.width", int64_t(w));
  p.set("render.height", int64_t(h));
  p.set("render.background", std::string("black"));
  p.set("render.show_box", false);
  p.set("render.show_axes", false);
  p.set("render.overlay", false);
  p.set("render.colormap", std::string("thesis"));  // pure blue -> green -> red
  p.set("camera.view", std::string("front"));
  return p;
}

struct Rig {
  std::unique_ptr<Backend> backend;
  std::unique_ptr<render::RenderDevice> device;
  std::unique_ptr<render::UiContext> ui;
  std::unique_ptr<render::Renderer> renderer;
  Rig(const std::string& name, uint32_t w, uint32_t h) {
    const masav::vk::ContextOptions o = test::graphics_options();
    backend = name == "cpu" ? std::unique_ptr<Backend>(new cpu::CpuBackend(1))
                            : render::open_compute_backend(name, "", o);
    device = std::make_unique<render::RenderDevice>(*backend, o);
    ui = std::make_unique<render::UiContext>();
    renderer = std::make_unique<render::Renderer>(*device, *ui, w, h);
  }
  Frame draw(const scene::SceneView& v, const scene::ParamSet& p) {
    render::FrameRequest f;
    f.view = &v;
    f.params = &p;
    f.readback = true;
    renderer->render(f);
    return Frame{renderer->width(), renderer->height(), renderer->pixels()};
  }
};

// Pixel of a world point under the camera the renderer used.
std::pair<int, int> project(const render::Camera& c, float x, float y, float z, uint32_t w,
                            uint32_t h) {
  const glm::vec4 clip = c.view_proj * glm::vec4(x, y, z, 1.0f);
  const glm::vec2 ndc(clip.x / clip.w, clip.y / clip.w);
  return {int(std::floor((ndc.x * 0.5f + 0.5f) * float(w))),
          int(std::floor((ndc.y * 0.5f + 0.5f) * float(h)))};
}

struct Points {
  Buffer<Real4> pos;
  Buffer<float> scalar;
  scene::SceneView view;
};

Points make_points(Backend& b, const std::vector<Vec4f>& p, const std::vector<float>& s) {
  Points pts{
      b.create<Real4>(p.size(), "test points"), b.create<float>(s.size(), "test scalars"), {}};
  b.upload(pts.pos, p);
  b.upload(pts.scalar, s);
  scene::PointLayer pl;
  pl.positions = &pts.pos;
  pl.count = uint32_t(p.size());
  pl.from = scene::PointLayer::ScalarFrom::buffer;
  pl.scalar = &pts.scalar.impl();
  pl.scalar_lo = 0;
  pl.scalar_hi = 1;
  pl.version = 1;
  pts.view.points = pl;
  return pts;
}

}  // namespace

TEST_CASE("points land where the camera projects them, in the colour map's colours") {
  const uint32_t W = 120, H = 90;
  scene::ParamSet p = plain_params(W, H);
  p.set("render.blend", std::string("additive"));  // the sprite's centre is the map colour
  p.set("render.point_size", 9.0);
  const std::vector<Vec4f> pos = {
      {0.2f, 0.5f, 0.25f, 0}, {0.5f, 0.5f, 0.5f, 0}, {0.8f, 0.5f, 0.75f, 0}};
  const std::vector<float> scalar = {0.0f, 0.5f, 1.0f};
  const Rgb expected[3] = {{0, 0, 255}, {0, 255, 0}, {255, 0, 0}};
  std::vector<Frame> frames;
  for (const char* path : {"vulkan", "cpu"}) {
    CAPTURE(path);
    Rig rig(path, W, H);
    CHECK((rig.device->shared() != nullptr) == (std::string(path) == "vulkan"));
    Points pts = make_points(*rig.backend, pos, scalar);
    const Frame f = rig.draw(pts.view, p);
    for (int i = 0; i < 3; ++i) {
      const auto [x, y] = project(rig.renderer->camera(), pos[i].x, pos[i].y, pos[i].z, W, H);
      CAPTURE(i);
      REQUIRE(x >= 2);
      REQUIRE(x < int(W) - 2);
      // The sprite's centre pixel, within the falloff of being off the pixel centre.
      const Rgb c = f.brightest(x, y, 1);
      CHECK(std::abs(c.r - expected[i].r) <= 20);
      CHECK(std::abs(c.g - expected[i].g) <= 20);
      CHECK(std::abs(c.b - expected[i].b) <= 20);
    }
    // z up, front view: the higher point is higher on screen.
    CHECK(project(rig.renderer->camera(), 0.5f, 0.5f, 0.9f, W, H).second <
          project(rig.renderer->camera(), 0.5f, 0.5f, 0.1f, W, H).second);
    // Far from every point: the clear colour.
    const Rgb corner = f.at(3, int(H) - 4);
    CHECK(corner.r + corner.g + corner.b < 30);
    frames.push_back(f);
  }
  // The copy path draws exactly what the shared-device path draws.
  CHECK(frames[0].px == frames[1].px);
}

TEST_CASE("opaque sprites are depth-tested: the nearer of two overlapping points wins") {
  Rig rig("vulkan", 80, 80);
  scene::ParamSet p = plain_params(80, 80);
  p.set("render.point_size", 12.0);
  // Front view looks along +y: y = 0.3 is nearer. The far point is drawn second.
  Points pts =
      make_points(*rig.backend, {{0.5f, 0.3f, 0.5f, 0}, {0.5f, 0.7f, 0.5f, 0}}, {0.0f, 1.0f});
  const Frame f = rig.draw(pts.view, p);
  const auto [x, y] = project(rig.renderer->camera(), 0.5f, 0.5f, 0.5f, 80, 80);
  const Rgb c = f.at(x, y);
  CHECK(c.b > 100);
  CHECK(c.r < 30);
  // Additive sprites do not hide each other: both colours add up.
  p.set("render.blend", std::string("additive"));
  const Frame g = rig.draw(pts.view, p);
  const Rgb d = g.brightest(x, y, 1);
  CHECK(d.b > 150);
  CHECK(d.r > 150);
}

// Two spheres, the second 0.9 radii to the right and 0.3 radii farther: at its centre, its own
// surface is nearer than the first sphere's, whose centre is nearer. A sphere impostor
// with its own depth shows the second there; a flat sprite at its centre's depth shows the first.
TEST_CASE("sphere impostors are lit and depth-correct: intersecting spheres cut each other") {
  const uint32_t W = 96, H = 96;
  Rig rig("vulkan", W, H);
  scene::ParamSet p = plain_params(W, H);
  p.set("render.point_size", 30.0);
  rig.draw({}, p);  // the camera for this frame size
  const render::Camera& cam = rig.renderer->camera();
  const float r = 0.5f * 30.0f * cam.distance / (0.5f * std::abs(cam.proj[1][1]) * float(H));
  // Front view: the camera looks along +y (smaller y is nearer), x to the right.
  const Vec4f a{0.5f - 0.45f * r, 0.4f, 0.5f, 0}, b{0.5f + 0.45f * r, 0.4f + 0.3f * r, 0.5f, 0};
  Points pts = make_points(*rig.backend, {a, b}, {1.0f, 0.0f});  // red, blue (thesis map)
  const auto [ax, ay] = project(cam, a.x, a.y, a.z, W, H);
  const auto [bx, by] = project(cam, b.x, b.y, b.z, W, H);
  const Frame spheres = rig.draw(pts.view, p);
  const Rgb at_a = spheres.at(ax, ay), at_b = spheres.at(bx, by);
  MESSAGE("spheres: centre a " << at_a.r << "," << at_a.b << "; centre b " << at_b.r << ","
                               << at_b.b);
  CHECK(at_a.r > 100);
  CHECK(at_a.b < 30);
  CHECK(at_b.b > 100);  // the second sphere's surface is in front of the first one there
  CHECK(at_b.r < 30);
  // Lit: the side towards the lamp (above left of the camera) is brighter than the far side.
  const int off = int(0.3f * r / (2.0f * r) * 30.0f);
  const Rgb lit_side = spheres.at(ax - off, ay - off), dark_side = spheres.at(ax - off, ay + off);
  CHECK(lit_side.r > dark_side.r + 20);
  // Flat sprites (the same points) get their centre's depth: the first point hides the second.
  p.set("render.point_style", std::string("sprites"));
  const Frame sprites = rig.draw(pts.view, p);
  const Rgb flat_b = sprites.at(bx, by);
  CHECK(flat_b.r > 60);  // the first sphere's side, darker than its centre
  CHECK(flat_b.b < 30);
}

// A slab of spheres (a lattice 0.8 radii apart, 3 layers deep) seen face on: the fluid surface
// covers it without holes, and its shading is smooth where the spheres' is bumpy.
TEST_CASE("the fluid surface is one connected, smoothly shaded sheet over the particles") {
  const uint32_t W = 160, H = 120;
  Rig rig("vulkan", W, H);
  scene::ParamSet p = plain_params(W, H);
  p.set("render.point_size", 8.0);
  rig.draw({}, p);
  const render::Camera& cam = rig.renderer->camera();
  const float r = 0.5f * 8.0f * cam.distance / (0.5f * std::abs(cam.proj[1][1]) * float(H));
  std::vector<Vec4f> pos;
  const float step = 0.8f * r;
  for (int k = 0; k < 3; ++k)
    for (float z = 0.25f; z <= 0.75f; z += step)
      for (float x = 0.2f; x <= 0.8f; x += step) pos.push_back({x, 0.45f + float(k) * step, z, 0});
  Points pts = make_points(*rig.backend, pos, std::vector<float>(pos.size(), 0.5f));
  const auto [x0, y0] = project(cam, 0.3f, 0.45f, 0.65f, W, H);  // inside the slab's face
  const auto [x1, y1] = project(cam, 0.7f, 0.45f, 0.35f, W, H);
  REQUIRE(x1 - x0 > 20);
  REQUIRE(y1 - y0 > 15);
  struct Stats {
    size_t covered = 0, n = 0;
    double mean = 0, sd = 0;
  };
  auto stats = [&](const Frame& f) {
    Stats s;
    std::vector<double> v;
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) {
        const Rgb c = f.at(x, y);
        ++s.n;
        s.covered += c.r + c.g + c.b > 60;
        v.push_back(c.r + c.g + c.b);
      }
    for (double q : v) s.mean += q / double(v.size());
    for (double q : v) s.sd += (q - s.mean) * (q - s.mean) / double(v.size());
    s.sd = std::sqrt(s.sd);
    return s;
  };
  const Stats bumpy = stats(rig.draw(pts.view, p));
  p.set("render.point_style", std::string("surface"));
  const Frame surface = rig.draw(pts.view, p);
  const Stats smooth = stats(surface);
  MESSAGE("spheres: covered " << bumpy.covered << "/" << bumpy.n << ", mean " << bumpy.mean
                              << ", sd " << bumpy.sd << "; surface: covered " << smooth.covered
                              << ", mean " << smooth.mean << ", sd " << smooth.sd);
  CHECK(smooth.covered == smooth.n);  // connected: no holes between the particles
  CHECK(smooth.sd < 0.2 * bumpy.sd);  // one smooth sheet, not a sphere per particle
  CHECK(smooth.mean > 60);            // and drawn, in the colour map's green
  const Rgb mid = surface.at((x0 + x1) / 2, (y0 + y1) / 2);
  CHECK(mid.g > mid.r + 20);
  CHECK(mid.g > mid.b + 20);
  // Outside the slab: nothing drawn.
  const Rgb corner = surface.at(3, 3);
  CHECK(corner.r + corner.g + corner.b < 30);
  // The surface needs opaque points: with additive glow the combination is refused.
  p.set("render.blend", std::string("additive"));
  try {
    render::check_render_params(p);
    FAIL("surface with additive blending was accepted");
  } catch (const Error& e) {
    CHECK(std::string(e.what()).find("render.point_style") != std::string::npos);
    CHECK(std::string(e.what()).find("render.blend") != std::string::npos);
  }
}

// Drops three radii in front of the slab: their own disks aside, the sheet behind them is shaded
// as without them. A filter that lets the drops pull on the sheet's depth leaves halos, and a
// rows-then-columns filter stretches them into vertical streaks.
TEST_CASE("drops in front of the fluid surface leave the sheet behind them undisturbed") {
  const uint32_t W = 320, H = 240;
  Rig rig("vulkan", W, H);
  scene::ParamSet p = plain_params(W, H);
  p.set("render.point_size", 8.0);
  p.set("render.point_style", std::string("surface"));
  rig.draw({}, p);
  const render::Camera& cam = rig.renderer->camera();
  const float focal = 0.5f * std::abs(cam.proj[1][1]) * float(H);
  const float r = 0.5f * 8.0f * cam.distance / focal;
  std::vector<Vec4f> slab;
  const float step = 0.8f * r;
  for (int k = 0; k < 3; ++k)
    for (float z = 0.25f; z <= 0.75f; z += step)
      for (float x = 0.2f; x <= 0.8f; x += step) slab.push_back({x, 0.45f + float(k) * step, z, 0});
  const std::vector<std::array<float, 2>> drops_xz = {{0.4f, 0.5f}, {0.6f, 0.45f}, {0.5f, 0.6f}};
  std::vector<Vec4f> with_drops = slab;
  for (const auto& d : drops_xz) with_drops.push_back({d[0], 0.45f - 3.0f * r, d[1], 0});
  Points a = make_points(*rig.backend, slab, std::vector<float>(slab.size(), 0.5f));
  const Frame sheet = rig.draw(a.view, p);
  Points b = make_points(*rig.backend, with_drops, std::vector<float>(with_drops.size(), 0.5f));
  const Frame dropped = rig.draw(b.view, p);
  // A drop's disk on screen is 8 px wide; the sheet is compared beyond 1.5 disk radii of it.
  std::vector<std::pair<int, int>> centres;
  for (const auto& d : drops_xz) centres.push_back(project(cam, d[0], 0.45f - 3.0f * r, d[1], W, H));
  const auto [x0, y0] = project(cam, 0.3f, 0.45f, 0.7f, W, H);
  const auto [x1, y1] = project(cam, 0.7f, 0.45f, 0.3f, W, H);
  size_t compared = 0, disturbed = 0, disturbed_near = 0;
  int worst = 0;
  for (int y = std::min(y0, y1); y <= std::max(y0, y1); ++y)
    for (int x = std::min(x0, x1); x <= std::max(x0, x1); ++x) {
      double nearest = 1e9;
      for (const auto& [cx, cy] : centres) nearest = std::min(nearest, std::hypot(x - cx, y - cy));
      if (nearest < 6.0) continue;  // the drop itself
      const Rgb u = sheet.at(x, y), v = dropped.at(x, y);
      const int diff = std::max({std::abs(u.r - v.r), std::abs(u.g - v.g), std::abs(u.b - v.b)});
      ++compared;
      worst = std::max(worst, diff);
      if (diff > 12) {
        ++disturbed;
        disturbed_near += nearest < 10.0;
      }
    }
  MESSAGE("sheet pixels compared " << compared << ", disturbed (> 12/255) " << disturbed << " ("
                                   << disturbed_near << " within 10 px of a drop), worst "
                                   << worst);
  REQUIRE(compared > 1200);
  CHECK(double(disturbed) < 0.01 * double(compared));
}

TEST_CASE("a kernel's image fills the background and the box is drawn over it") {
  const uint32_t W = 64, H = 48;
  Rig rig("vulkan", W, H);
  scene::ParamSet p = plain_params(W, H);
  // A 2x2 RGBA8 image: red, green / blue, white (row 0 at the top).
  auto img = rig.backend->create<uint32_t>(4, "test image");
  rig.backend->upload(img,
                      std::vector<uint32_t>{0xFF0000FFu, 0xFF00FF00u, 0xFFFF0000u, 0xFFFFFFFFu});
  scene::SceneView v;
  scene::ImageLayer il;
  il.pixels = &img.impl();
  il.width = il.height = 2;
  il.format = scene::ImageLayer::Format::rgba8;
  il.version = 1;
  v.background = il;
  Frame f = rig.draw(v, p);
  const Rgb tl = f.at(3, 3), tr = f.at(int(W) - 4, 3), bl = f.at(3, int(H) - 4),
            br = f.at(int(W) - 4, int(H) - 4);
  CHECK((tl.r > 240 && tl.g < 15 && tl.b < 15));
  CHECK((tr.g > 240 && tr.r < 15 && tr.b < 15));
  CHECK((bl.b > 240 && bl.r < 15 && bl.g < 15));
  CHECK((br.r > 240 && br.g > 240 && br.b > 240));
  // gain and gamma: 0.5 * 1^gamma.
  v.background->gain = 0.5f;
  v.background->gamma = 3.0f;
  f = rig.draw(v, p);
  CHECK(std::abs(f.at(3, 3).r - 128) <= 2);

  // The box, over a black background: its front bottom edge is grey where the camera puts it.
  v.background.reset();
  p.set("render.show_box", true);
  f = rig.draw(v, p);
  const auto [x, y] = project(rig.renderer->camera(), 0.5f, 0.0f, 0.0f, W, H);
  const Rgb e = f.brightest(x, y, 1);
  CHECK(e.r > 100);
  CHECK(std::abs(e.r - e.g) < 30);
}

TEST_CASE("the particle scene renders non-blank, changing frames with the overlay") {
  scene::SceneFile file = scene::default_scene("particles");
  file.params.set("particles.count", int64_t(8000));
  file.params.set("particles.grid_cells", int64_t(16));
  file.params.set("particles.drift_speed", 0.5);
  file.params.set("render.width", int64_t(200));
  file.params.set("render.height", int64_t(150));
  render::PlayerOptions po;
  po.backend = "vulkan";
  po.graphics = test::graphics_options();
  po.cache_dir = test::cache_dir();
  render::ScenePlayer player(file, po);
  auto frame = [&](double t) {
    player.clock().time_s = t;
    player.update();
    render::FrameRequest req;
    req.readback = true;
    player.draw(req);
    return Frame{player.renderer().width(), player.renderer().height(), player.renderer().pixels()};
  };
  const Frame a = frame(0.0), b = frame(1.0);
  // Not blank: many pixels carry point colours.
  size_t colored = 0;
  for (uint32_t y = 0; y < a.h; ++y)
    for (uint32_t x = 0; x < a.w; ++x) colored += lit(a.at(int(x), int(y)));
  CHECK(colored > a.w * a.h / 20);
  // The drift moves the points: the frames differ.
  CHECK(fraction_differing(a, b) > 0.02);
  // The overlay's text is in the top-left corner: bright, near-white pixels.
  size_t text = 0;
  for (int y = 4; y < 40; ++y)
    for (int x = 4; x < 120; ++x) {
      const Rgb c = a.at(x, y);
      text += c.r > 200 && c.g > 200 && c.b > 200;
    }
  CHECK(text > 30);
  // Without the overlay, the corner shows the scene instead.
  player.scene().set("render.overlay", false);
  const Frame c = frame(1.0);
  CHECK(fraction_differing(b, c) > 0.01);
}

TEST_CASE("frames are written as PNG and read back unchanged") {
  const std::string path = (std::filesystem::temp_directory_path() / "masav_render_test.png");
  std::vector<uint8_t> px(16 * 8 * 4);
  for (size_t i = 0; i < px.size(); ++i) px[i] = uint8_t(i * 7);
  render::write_png(path, 16, 8, px);
  const render::Rgba8Image img = render::read_png(path);
  CHECK(img.width == 16);
  CHECK(img.height == 8);
  CHECK(img.pixels == px);
  std::filesystem::remove(path);
  CHECK_THROWS_AS(render::write_png("/proc/masav/x.png", 16, 8, px), Error);
}

TEST_CASE("demo screenshots" * doctest::skip(std::getenv("MASAV_DEMO_SHOTS") == nullptr)) {
  // Written by tests/data/demo_script.txt: a (start), b (brighter), c (top view),
  // d (the speed scene), e (the speed scene on the CPU backend).
  const std::string dir = std::getenv("MASAV_DEMO_SHOTS");
  auto load = [&](const char* name) {
    const render::Rgba8Image img = render::read_png(dir + "/" + name);
    return Frame{img.width, img.height, img.pixels};
  };
  const Frame a = load("a.png"), b = load("b.png"), c = load("c.png"), d = load("d.png"),
              e = load("e.png");
  // The scene area: left of the panel, below the overlay (the bottom-left quarter).
  auto region_mean = [](const Frame& f) {
    double s = 0;
    size_t n = 0;
    for (uint32_t y = f.h / 2; y < f.h; ++y)
      for (uint32_t x = 0; x < f.w / 2; ++x, ++n) {
        const Rgb c = f.at(int(x), int(y));
        s += c.r + c.g + c.b;
      }
    return s / double(n);
  };
  // Red-dominated pixels among lit ones: inferno's dark reds and oranges, never viridis (whose
  // yellow has nearly as much green as red).
  auto warm_fraction = [](const Frame& f) {
    size_t warm = 0, lit_px = 0;
    for (uint32_t y = f.h / 2; y < f.h; ++y)
      for (uint32_t x = 0; x < f.w / 2; ++x) {
        const Rgb c = f.at(int(x), int(y));
        if (!lit(c)) continue;
        ++lit_px;
        warm += c.r > 1.4 * std::max(c.g, c.b) + 8;
      }
    return lit_px ? double(warm) / double(lit_px) : 0.0;
  };
  for (const Frame* f : {&a, &b, &c, &d, &e}) CHECK(f->mean() > 5.0);
  MESSAGE("scene-area mean a " << region_mean(a) << ", b " << region_mean(b) << "; warm a "
                               << warm_fraction(a) << ", d " << warm_fraction(d) << ", e "
                               << warm_fraction(e) << "; b/c differ " << fraction_differing(b, c));
  CHECK(region_mean(b) > 1.3 * region_mean(a));  // brighter after `set render.brightness`
  CHECK(fraction_differing(b, c) > 0.05);        // another viewpoint
  CHECK(warm_fraction(a) < 0.05);                // viridis neighbour counts
  CHECK(warm_fraction(d) > 0.2);                 // inferno speeds after `scene`
  CHECK(warm_fraction(e) > 0.2);                 // the same scene computed on the CPU
  // The panel (an ImGui window) covers the right side: dark grey with light text.
  size_t panel_text = 0;
  for (uint32_t y = 20; y < a.h / 2; ++y)
    for (uint32_t x = a.w - a.w / 4; x < a.w - 20; ++x) {
      const Rgb c = a.at(int(x), int(y));
      panel_text += c.r > 180 && c.g > 180 && c.b > 180;
    }
  CHECK(panel_text > 50);
}

TEST_CASE("demo layout" * doctest::skip(std::getenv("MASAV_DEMO_SHOTS") == nullptr)) {
  // a.png: the panel expanded; f.png: collapsed (tests/data/demo_script.txt). Each screenshot has
  // its layout beside it: lines "NAME x y width height".
  const std::string dir = std::getenv("MASAV_DEMO_SHOTS");
  struct Rect {
    uint32_t x = 0, y = 0, w = 0, h = 0;
  };
  struct Layout {
    Rect window, scene, panel;
    int expanded = -1;
  };
  auto load_layout = [&](const char* name) {
    std::ifstream f(dir + "/" + name);
    Layout l;
    std::string key;
    while (f >> key) {
      if (key == "expanded") {
        f >> l.expanded;
        continue;
      }
      Rect r;
      f >> r.x >> r.y >> r.w >> r.h;
      (key == "window" ? l.window : key == "scene" ? l.scene : l.panel) = r;
    }
    return l;
  };
  auto load = [&](const char* name) {
    const render::Rgba8Image img = render::read_png(dir + "/" + name);
    return Frame{img.width, img.height, img.pixels};
  };
  const Layout la = load_layout("a.png.layout"), lf = load_layout("f.png.layout");
  const Frame a = load("a.png"), f = load("f.png");
  REQUIRE(la.expanded == 1);
  REQUIRE(lf.expanded == 0);
  for (const Layout* l : {&la, &lf}) {
    CHECK(l->window.w == a.w);
    CHECK(l->window.h == a.h);
    // Side by side: the scene's viewport ends where the panel begins, both full height.
    CHECK(l->scene.x + l->scene.w == l->panel.x);
    CHECK(l->panel.x + l->panel.w == l->window.w);
    CHECK(l->scene.h == l->window.h);
    CHECK(l->panel.h == l->window.h);
  }
  CHECK(la.panel.w >= 300);              // room for the labels
  CHECK(lf.panel.w <= 48);               // collapsed: a strip
  CHECK(lf.scene.w > la.scene.w + 250);  // the scene takes the panel's place
  // The most common colour of a rectangle: the panel's background, or the scene's clear colour.
  auto mode = [](const Frame& fr, uint32_t x0, uint32_t x1) {
    std::map<uint32_t, size_t> n;
    for (uint32_t y = 0; y < fr.h; y += 2)
      for (uint32_t x = x0; x < x1; x += 2) {
        const Rgb c = fr.at(int(x), int(y));
        ++n[uint32_t(c.r) << 16 | uint32_t(c.g) << 8 | uint32_t(c.b)];
      }
    return std::max_element(n.begin(), n.end(),
                            [](auto& p, auto& q) { return p.second < q.second; })
        ->first;
  };
  const uint32_t scene_bg = mode(a, 0, la.scene.w), panel_bg = mode(a, la.panel.x, a.w);
  MESSAGE(fmt::format("scene background {:06x}, panel background {:06x}", scene_bg, panel_bg));
  CHECK(scene_bg != panel_bg);
  // Collapsed, the scene's background (f shows another scene) fills where the panel was.
  const uint32_t f_scene_bg = mode(f, 0, la.scene.w);
  CHECK(f_scene_bg != panel_bg);
  CHECK(mode(f, la.panel.x, lf.panel.x) == f_scene_bg);
}

int main(int argc, char** argv) {
  BackendStatus s;
  for (const BackendStatus& b : list_backends())
    if (b.name == "vulkan") s = b;
  if (!s.available) {
    fmt::print("SKIPPED: Vulkan is not available here: {}\n", s.reason);
    return 77;
  }
  masav::vk::set_validation_handler([](const std::string& msg) {
    if (doctest::is_running_in_test)
      FAIL_CHECK(msg);
    else
      fmt::print(stderr, "{}\n", msg);
  });
  doctest::Context ctx(argc, argv);
  return ctx.run();
}
