// The demo's transfer function editor without a window (app/demo/tf_points.h): its point edits
// keep a valid function, Save TF and Load TF round-trip, the histogram it draws, and the scene
// keys it writes (`transfer`, the points inline): their checks, the stages an edit reruns, and
// that the inline points render as the same points in a `--tf` file do.
#include <doctest/doctest.h>

#include <cmath>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "app/demo/tf_points.h"
#include "engine/core/error.h"
#include "engine/cpu/cpu_backend.h"
#include "engine/volume/transfer_function.h"
#include "engine/volume/value_histogram.h"
#include "engine/volume/volume_scene.h"
#include "registry/scene_catalog.h"
#include "temp_dir.h"
#include "tests/error_of.h"

using namespace masav;
using masav::test::error_of;
using namespace masav::app;

namespace {

bool ascending_in_unit_range(const std::vector<TransferPoint>& pts) {
  for (size_t i = 0; i < pts.size(); ++i) {
    const TransferPoint& p = pts[i];
    for (double x : {p.value, p.r, p.g, p.b, p.a})
      if (!(x >= 0 && x <= 1)) return false;
    if (i > 0 && !(p.value > pts[i - 1].value)) return false;
  }
  return true;
}

bool same_points(const std::vector<TransferPoint>& a, const std::vector<TransferPoint>& b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i)
    if (a[i].value != b[i].value || a[i].r != b[i].r || a[i].g != b[i].g || a[i].b != b[i].b ||
        a[i].a != b[i].a)
      return false;
  return true;
}

void write_ramp(const std::string& path) {
  std::vector<char> v(8 * 6 * 4);
  for (size_t i = 0; i < v.size(); ++i) v[i] = char(i % 200);
  std::ofstream(path, std::ios::binary).write(v.data(), std::streamsize(v.size()));
}

std::unique_ptr<scene::SceneInstance> ramp_scene(Backend& b, const std::string& file) {
  scene::ParamSet p = scene::default_params(scene::find_scene_type("volume"));
  volume::set_volume_file_options(p, {file, {8, 6, 4}, "uint8"});
  p.set("render.width", int64_t(40));
  p.set("render.height", int64_t(28));
  return scene::find_scene_type("volume").create(b, p);
}

// The raymarched image (the CPU reference holds doubles).
std::vector<Vec4d> image_of(cpu::CpuBackend& b, const scene::SceneInstance& s) {
  const scene::SceneView v = s.view();  // a value: the layer must outlive this call's temporary
  REQUIRE(v.background.has_value());
  std::vector<Vec4d> img(size_t(v.background->width) * v.background->height);
  REQUIRE(b.real_bytes() == sizeof(double));
  b.download_bytes(*v.background->pixels, img.data(), img.size() * sizeof(Vec4d), 0);
  return img;
}

}  // namespace

TEST_CASE("tf editor: a point added between two takes the function's colour there") {
  std::vector<TransferPoint> pts = {{0.0, 0, 0, 1, 0}, {1.0, 1, 0, 0, 1}};
  const auto i = add_tf_point(pts, 0.25);
  REQUIRE(i);
  CHECK(*i == 1);
  REQUIRE(pts.size() == 3);
  CHECK(pts[1].value == 0.25);
  CHECK(pts[1].r == doctest::Approx(0.25));
  CHECK(pts[1].b == doctest::Approx(0.75));
  CHECK(pts[1].a == doctest::Approx(0.25));
  // The function is unchanged until the point is edited.
  const auto before = volume::resample_transfer({{0.0, 0, 0, 1, 0}, {1.0, 1, 0, 0, 1}}, 64);
  const auto after = volume::resample_transfer(pts, 64);
  for (size_t k = 0; k < before.size(); ++k) CHECK(after[k].x == doctest::Approx(before[k].x));
  // Outside [0, 1] clamps; on top of a point (closer than kMinTfGap) adds nothing.
  CHECK_FALSE(add_tf_point(pts, -0.5));
  CHECK_FALSE(add_tf_point(pts, 0.25 + kMinTfGap / 2));
  CHECK(pts.size() == 3);
  CHECK(ascending_in_unit_range(pts));
}

TEST_CASE("tf editor: a dragged point stays between its neighbours and in [0, 1]") {
  std::vector<TransferPoint> pts = volume::default_transfer_points();
  move_tf_point(pts, 2, 0.99, 2.0);  // past the next point, opacity over 1
  CHECK(pts[2].value == doctest::Approx(pts[3].value - kMinTfGap));
  CHECK(pts[2].a == 1.0);
  move_tf_point(pts, 2, -3.0, -1.0);  // before the previous point, opacity under 0
  CHECK(pts[2].value == doctest::Approx(pts[1].value + kMinTfGap));
  CHECK(pts[2].a == 0.0);
  move_tf_point(pts, 0, -1.0, 0.5);
  CHECK(pts[0].value == 0.0);
  move_tf_point(pts, pts.size() - 1, 7.0, 0.5);
  CHECK(pts.back().value == 1.0);
  set_tf_colour(pts, 1, 1.5, -0.2, 0.5, 0.25);
  CHECK(pts[1].r == 1.0);
  CHECK(pts[1].g == 0.0);
  CHECK(pts[1].b == 0.5);
  CHECK(ascending_in_unit_range(pts));
  // Every edit leaves what the `--tf` parser accepts.
  CHECK_NOTHROW(volume::parse_inline_transfer(volume::format_inline_transfer(pts), "t"));
}

TEST_CASE("tf editor: delete keeps at least two points") {
  std::vector<TransferPoint> pts = volume::default_transfer_points();
  while (pts.size() > kMinTfPoints) CHECK(delete_tf_point(pts, 1));
  CHECK_FALSE(delete_tf_point(pts, 0));
  CHECK(pts.size() == kMinTfPoints);
  CHECK_FALSE(delete_tf_point(pts, 7));  // no such point
}

TEST_CASE(
    "tf editor: Save TF then Load TF gives the same points; a bad file names line and field") {
  test::TempDir t("masav_tf_editor_files");
  write_ramp(t.file("ramp.raw"));
  cpu::CpuBackend cpu(2);
  auto s = ramp_scene(cpu, t.file("ramp.raw"));
  TfEditorState e;
  sync_tf_editor(e, s->params(), "raymarch");
  CHECK(same_points(e.points, volume::default_transfer_points()));
  // Points with values no short decimal holds.
  e.points = {
      {0.0, 0.1, 0.2, 0.3, 0.0}, {1.0 / 3, 2.0 / 3, 0.123456789, 1.0 / 7, 0.5}, {1.0, 1, 0, 0, 1}};
  const std::vector<TransferPoint> saved = e.points;
  save_tf_file(e, t.file("tf.txt"));
  CHECK_FALSE(e.message_is_error);
  CHECK(same_points(volume::load_transfer_points(t.file("tf.txt")), saved));
  TfEditorState other;
  load_tf_file(other, *s, "raymarch", t.file("tf.txt"));
  CHECK_FALSE(other.message_is_error);
  CHECK(same_points(other.points, saved));
  // The scene holds them inline, and they read back the same.
  CHECK(same_points(volume::parse_inline_transfer(s->params().get_text("raymarch.transfer"), "t"),
                    saved));
  // A refused file: the message names the file, the line and the field; the scene keeps its points.
  std::ofstream(t.file("bad.txt")) << "0 0 0 1 0\n0.5 0 1.5 0 1\n";
  load_tf_file(other, *s, "raymarch", t.file("bad.txt"));
  CHECK(other.message_is_error);
  CHECK(other.message.find("bad.txt") != std::string::npos);
  CHECK(other.message.find("line 2 field g = 1.5") != std::string::npos);
  CHECK(other.message.find("[0, 1]") != std::string::npos);
  CHECK(same_points(volume::parse_inline_transfer(s->params().get_text("raymarch.transfer"), "t"),
                    saved));
  load_tf_file(other, *s, "raymarch", t.file("missing.txt"));
  CHECK(other.message_is_error);
  save_tf_file(e, t.file("no/such/folder/tf.txt"));
  CHECK(e.message_is_error);
  CHECK(e.message.find("cannot write") != std::string::npos);
}

TEST_CASE("tf editor: the histogram of a known volume") {
  const std::vector<double> values = {0, 0, 0, 0, 1, 2, 3, 4, 4, -5, 9, std::nan("")};
  // Over [0, 4] in 4 bins: [0, 1) holds 0 x4 and the clamped -5; the top value in the last bin,
  // with the clamped 9; NaN not counted.
  CHECK(volume::value_histogram(values, 0, 4, 4) == std::vector<uint32_t>{5, 1, 1, 4});
  CHECK(volume::value_histogram(values, 2, 2, 2) == std::vector<uint32_t>{11, 0});
  CHECK_THROWS_AS(volume::value_histogram(values, 0, 1, 0), Error);
  const std::vector<float> h = volume::log_heights({0, 1, 3, 0});
  CHECK(h[0] == 0.0f);
  CHECK(h[2] == doctest::Approx(1.0));
  CHECK(h[1] == doctest::Approx(std::log(2.0) / std::log(4.0)));
  CHECK(volume::log_heights({0, 0}) == std::vector<float>{0, 0});
  // The scene's own: a ramp 0..199 repeating over 192 voxels (values 0..191), 4 bins of 48.
  test::TempDir t("masav_tf_editor_histogram");
  write_ramp(t.file("ramp.raw"));
  cpu::CpuBackend cpu(2);
  auto s = ramp_scene(cpu, t.file("ramp.raw"));
  scene::FrameClock clock;
  s->update(clock);
  CHECK(s->volume_version() > 0);
  CHECK(s->value_histogram(4) == std::vector<uint32_t>{48, 48, 48, 48});
}

TEST_CASE("tf editor: the inline key's checks name the key, the point, the field and the range") {
  test::TempDir t("masav_tf_editor_keys");
  write_ramp(t.file("ramp.raw"));
  cpu::CpuBackend cpu(2);
  auto s = ramp_scene(cpu, t.file("ramp.raw"));
  const std::string range =
      error_of([&] { s->set("raymarch.transfer", std::string("0 0 0 1 0; 0.5 2 0 0 1")); });
  CHECK(range.find("scene: invalid raymarch.transfer point 2 field r = 2") != std::string::npos);
  CHECK(range.find("raymarch.transfer point 2 field r must be a number in [0, 1]") !=
        std::string::npos);
  CHECK(error_of([&] {
          s->set("raymarch.transfer", std::string(";;"));
        }).find("invalid raymarch.transfer = no entries") != std::string::npos);
  const std::string order =
      error_of([&] { s->set("raymarch.transfer", std::string("0.5 0 0 1 0; 0.25 1 0 0 1")); });
  CHECK(order.find("raymarch.transfer point 2 field value = 0.25") != std::string::npos);
  CHECK(order.find("greater than the previous value 0.5") != std::string::npos);
  const std::string count =
      error_of([&] { s->set("raymarch.transfer", std::string("0 0 0 1; 1 1 0 0 1")); });
  CHECK(count.find("raymarch.transfer point 1") != std::string::npos);
  CHECK(count.find("five numbers: value r g b a") != std::string::npos);
  CHECK(s->params().get_text("raymarch.transfer").empty());  // refused: the old value stays
  // Both keys set: refused, naming both.
  s->set("raymarch.transfer", std::string("0 0 0 1 0; 1 1 0 0 1"));
  const std::string both =
      error_of([&] { s->set("raymarch.transfer_file", std::string("tf.txt")); });
  CHECK(both.find("raymarch.transfer and raymarch.transfer_file = tf.txt are both set") !=
        std::string::npos);
  // The atom-volume scene's key is checked the same way.
  scene::ParamSet p = scene::default_params(scene::find_scene_type("atom-volume"));
  CHECK(p.has("volume.transfer"));
  CHECK(transfer_table(p) == std::optional<std::string>("volume"));
  CHECK(transfer_table(scene::default_params(scene::find_scene_type("particles"))) == std::nullopt);
}

TEST_CASE("tf editor: an edit reruns only transfer, bricks and raymarch, and renders as the file") {
  test::TempDir t("masav_tf_editor_render");
  write_ramp(t.file("ramp.raw"));
  cpu::CpuBackend cpu(2);
  auto s = ramp_scene(cpu, t.file("ramp.raw"));
  scene::FrameClock clock;
  s->update(clock);
  const std::vector<Vec4d> before = image_of(cpu, *s);
  // A red-only opaque ramp, through the script's verbs (what the panel's controls call).
  TfEditorState e;
  std::ofstream(t.file("red.txt")) << "0 0 0 0 0\n1 1 0 0 1\n";
  run_tf_words(e, *s, {"load", t.file("red.txt")}, "test");
  CHECK_FALSE(e.message_is_error);
  CHECK(s->update(clock).ran == std::vector<std::string>{"transfer", "bricks", "raymarch"});
  const std::vector<Vec4d> inline_image = image_of(cpu, *s);
  double red = 0, other = 0, change = 0;
  for (size_t i = 0; i < inline_image.size(); ++i) {
    red += inline_image[i].x;
    other += inline_image[i].y + inline_image[i].z;
    change += std::abs(inline_image[i].x - before[i].x) + std::abs(inline_image[i].z - before[i].z);
  }
  CHECK(red > 1.0);
  CHECK(other == 0.0);
  CHECK(change > 1.0);
  // The same points from the file key render the same image.
  reset_tf_points(*s, "raymarch");
  s->set("raymarch.transfer_file", t.file("red.txt"));
  CHECK(s->update(clock).ran == std::vector<std::string>{"transfer", "bricks", "raymarch"});
  const std::vector<Vec4d> file_image = image_of(cpu, *s);
  for (size_t i = 0; i < file_image.size(); ++i) CHECK(file_image[i].x == inline_image[i].x);
  // `tf point` edits the points the editor shows; `tf delete` refuses the last two.
  run_tf_words(e, *s, {"point", "0.5", "0", "1", "0", "0.5"}, "test");
  CHECK(e.points.size() == 3);
  CHECK(s->params().get_text("raymarch.transfer_file").empty());
  CHECK(s->params().get_text("raymarch.transfer") == "0 0 0 0 0; 0.5 0 1 0 0.5; 1 1 0 0 1");
  run_tf_words(e, *s, {"delete", "0.5"}, "test");
  CHECK(e.points.size() == 2);
  CHECK(error_of([&] {
          run_tf_words(e, *s, {"delete", "1"}, "script.txt:4");
        }).find("keeps at least 2 points") != std::string::npos);
  CHECK(error_of([&] {
          check_tf_words({"point", "0.5", "0", "1", "0"}, "script.txt:5");
        }).find("script.txt:5") != std::string::npos);
  CHECK(error_of([&] {
          check_tf_words({"point", "0.5", "0", "1", "0", "1.5"}, "s:6");
        }).find("tf point field a = 1.5") != std::string::npos);
  run_tf_words(e, *s, {"reset"}, "test");
  CHECK(same_points(e.points, volume::default_transfer_points()));
}
