// Scene files and their schema, the stage graph and its counters, the particle scene's stage
// skipping, and the cross-check (including comparisons that must fail). CPU reference only:
// the per-backend versions live in test_scene_backends.cpp.
#define DOCTEST_CONFIG_IMPLEMENT_WITH_MAIN
#include <doctest/doctest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>

#include "engine/core/error.h"
#include "engine/cpu/cpu_backend.h"
#include "engine/scene/scene.h"
#include "engine/scene/stage_cache.h"
#include "engine/util/chi_square.h"
#include "engine/verify/cross_check.h"
#include "registry/check_catalog.h"
#include "registry/common_tables.h"
#include "registry/scene_catalog.h"
#include "registry/scene_file.h"
#include "tests/error_of.h"

using namespace masav;
using masav::test::error_of;
using namespace masav::scene;

namespace {

SceneFile parse(const std::string& text) {
  return parse_scene(text, "test.toml");
}

}  // namespace

TEST_CASE("a scene file fills every parameter with its default") {
  const SceneFile f = parse("[scene]\ntype = \"particles\"\n[particles]\ncount = 1000\n");
  CHECK(f.type == "particles");
  CHECK(f.params.get_int("particles.count") == 1000);
  CHECK(f.params.get_int("particles.seed") == 1);
  CHECK(f.params.get_text("render.colormap") == "viridis");
  CHECK(f.params.get_real("camera.fov_deg") == 40.0);
  CHECK(f.params.get_flag("verify.enabled"));
  // Integers are accepted for reals; the type of the scene defaults to particles.
  const SceneFile g = parse("[render]\npoint_size = 5\n");
  CHECK(g.params.get_real("render.point_size") == 5.0);
}

TEST_CASE("the documented TOML of a scene reads back to the same parameters") {
  SceneFile f = default_scene("particles");
  f.params.set("particles.drift_speed", 0.125);
  f.params.set("render.blend", std::string("additive"));
  f.params.set("camera.yaw_deg", -12.5);
  for (bool help : {true, false}) {
    const SceneFile g = parse(scene_to_toml(f.params, help));
    for (const TableSchema* t : f.params.tables())
      for (const ParamSpec& p : t->params()) {
        const std::string path = t->name() + "." + p.key;
        CAPTURE(path);
        CHECK(g.params.get(path) == f.params.get(path));
      }
  }
}

TEST_CASE("every text parameter of every scene type reads back from the TOML masav writes") {
  // Quotes, backslashes, control characters, non-ASCII text and TOML's own syntax.
  const std::string hard[] = {"say \"hi\"", "C:\\dir\\", "tab\there", "line\nbreak", "bell\x07",
                              "\x7f del", "Wasserstoff \xc3\xa9\xe2\x84\x8f", "]\n[scene]\ntype = \"x\"",
                              "'single' \"\"\"triple\"\"\"", "# not a comment", ""};
  size_t tried = 0;
  for (const std::string& type : scene_type_names()) {
    CAPTURE(type);
    SceneFile f = default_scene(type);
    for (const TableSchema* t : f.params.tables())
      for (const ParamSpec& p : t->params()) {
        if (p.type != ParamType::text) continue;
        const std::string path = t->name() + "." + p.key;
        CAPTURE(path);
        for (const std::string& value : hard) {
          CAPTURE(value);
          try {
            f.params.set(path, value);
          } catch (const Error&) {
            continue;  // a text parameter with rules of its own (a path that must exist...)
          }
          ++tried;
          for (bool help : {true, false}) {
            const SceneFile g = parse(scene_to_toml(f.params, help));
            CHECK(g.params.get(path) == ParamValue(value));
          }
        }
        f.params.set(path, default_scene(type).params.get(path));
      }
  }
  CHECK(tried >= 20);
}

TEST_CASE("scene-file errors name the file, line, key, value and allowed range") {
  auto err = [](const std::string& text) { return error_of([&] { parse(text); }); };
  std::string e = err("[particles]\ncount = 0\n");
  CHECK(e.find("test.toml:2") != std::string::npos);
  CHECK(e.find("particles.count = 0") != std::string::npos);
  CHECK(e.find("an integer in [1, 4000000]") != std::string::npos);

  e = err("[particles]\ncout = 5\n");
  CHECK(e.find("particles.cout") != std::string::npos);
  CHECK(e.find("count, seed") != std::string::npos);  // the keys it knows

  e = err("[particle]\ncount = 5\n");
  CHECK(e.find("table = particle") != std::string::npos);
  CHECK(e.find("particles") != std::string::npos);

  e = err("[render]\ncolormap = \"rainbow\"\n");
  CHECK(e.find("render.colormap = \"rainbow\"") != std::string::npos);
  CHECK(e.find("one of viridis, inferno, thesis, grey") != std::string::npos);

  e = err("[particles]\ncount = \"many\"\n");
  CHECK(e.find("particles.count = \"many\"") != std::string::npos);

  e = err("[particles]\ncount = [1, 2]\n");
  CHECK(e.find("particles.count = [") != std::string::npos);

  e = err("[camera]\nfov_deg = nan\n");
  CHECK(e.find("camera.fov_deg = nan") != std::string::npos);

  e = err("[scene]\ntype = \"galaxy\"\n");
  CHECK(e.find("scene.type = galaxy") != std::string::npos);
  CHECK(e.find("one of particles") != std::string::npos);

  e = err("[particles\ncount = 1\n");
  CHECK(e.find("test.toml:1:") != std::string::npos);
  CHECK(e.find("malformed TOML") != std::string::npos);

  e = err("count = 3\n");
  CHECK(e.find("table = count") != std::string::npos);
}

TEST_CASE("missing and unreadable scene files are clear errors") {
  std::string e = error_of([] { load_scene_file("/nonexistent/scene.toml"); });
  CHECK(e.find("'/nonexistent/scene.toml' does not exist") != std::string::npos);
  e = error_of([] { load_scene_file("/tmp"); });
  CHECK(e.find("is a directory") != std::string::npos);
  const std::string bin = std::filesystem::temp_directory_path() / "masav_test_binary.toml";
  {
    std::ofstream out(bin, std::ios::binary);
    out.write("\0\1\2", 3);
  }
  e = error_of([&] { load_scene_file(bin); });
  CHECK(e.find("not a text file") != std::string::npos);
  std::filesystem::remove(bin);
}

TEST_CASE("parameters set at run time are validated, versioned and reported") {
  ParamSet p = default_params(find_scene_type("particles"));
  const uint64_t v0 = p.version("particles.count");
  CHECK(p.set("particles.count", int64_t(500)));
  CHECK_FALSE(p.set("particles.count", int64_t(500)));  // unchanged: no new version
  CHECK(p.version("particles.count") > v0);
  CHECK(p.set_from_string("render.brightness", "2.5"));
  CHECK(p.get_real("render.brightness") == 2.5);
  CHECK(p.set_from_string("render.show_box", "off"));
  CHECK_FALSE(p.get_flag("render.show_box"));
  CHECK(error_of([&] {
          p.set_from_string("render.brightness", "bright");
        }).find("render.brightness = bright") != std::string::npos);
  CHECK(error_of([&] {
          p.set_from_string("render.brightness", "17");
        }).find("a number in [0.0, 16.0]") != std::string::npos);
  CHECK(error_of([&] { p.set("nothing.here", true); }).find("table = nothing") !=
        std::string::npos);
  CHECK(p.changed_since(v0).size() == 3);
}

TEST_CASE("the stage graph runs a stage only when an input changed") {
  StageGraph g;
  g.add_input("a");
  g.add_input("b");
  std::map<std::string, int> runs;
  auto stage = [&](const char* name) {
    return [&runs, name] { return std::make_unique<LambdaStage>([&runs, name] { ++runs[name]; }); };
  };
  g.add_stage("x", {"a"}, stage("x"));
  g.add_stage("y", {"x", "b"}, stage("y"));
  g.add_stage("z", {"b"}, stage("z"));  // never reached below
  const std::vector<std::string> targets = {"y"};
  UpdateReport r = g.update(targets);
  CHECK(r.ran == std::vector<std::string>{"x", "y"});
  CHECK(r.created.size() == 2);
  r = g.update(targets);
  CHECK(r.ran.empty());
  CHECK(r.skipped.size() == 2);
  g.touch("b");
  r = g.update(targets);
  CHECK(r.ran == std::vector<std::string>{"y"});
  g.touch("a");
  r = g.update(targets);
  CHECK(r.ran == std::vector<std::string>{"x", "y"});
  CHECK(runs["x"] == 2);
  CHECK(runs["y"] == 3);
  CHECK_FALSE(g.created("z"));
  CHECK(g.counters("z").runs == 0);
  CHECK(g.counters("y").skips == 1);
  g.add_stage("loop1", {"loop2"}, stage("l"));
  g.add_stage("loop2", {"loop1"}, stage("l"));
  const std::vector<std::string> loop = {"loop1"};
  CHECK(error_of([&] { g.update(loop); }).find("depends on itself") != std::string::npos);
}

TEST_CASE("the stage graph tells a pending change from one input it is told to ignore") {
  StageGraph g;
  g.add_input("view");
  g.add_input("preview");
  int runs = 0;
  auto stage = [&runs] { return std::make_unique<LambdaStage>([&runs] { ++runs; }); };
  g.add_stage("light", {"view"}, stage);
  g.add_stage("raymarch", {"light", "preview"}, stage);
  const std::vector<std::string> targets = {"raymarch"};
  CHECK(g.pending("raymarch", "preview"));  // never ran
  g.update(targets);
  CHECK_FALSE(g.pending("raymarch"));
  CHECK_FALSE(g.pending("raymarch", "preview"));
  g.touch("preview");  // a refinement the caller asked for itself
  CHECK(g.pending("raymarch"));
  CHECK_FALSE(g.pending("raymarch", "preview"));
  g.update(targets);
  g.touch("view");  // reaches the raymarch through the stage it reads
  CHECK(g.pending("raymarch", "preview"));
  CHECK(g.pending("light", "preview"));
  g.update(targets);
  CHECK_FALSE(g.pending("raymarch", "preview"));
  CHECK(runs == 5);
  CHECK_FALSE(g.pending("view"));  // an input is never pending
}

TEST_CASE("a cached stage computes once, then loads from disk until its parameters change") {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / "masav_stage_cache_test";
  fs::remove_all(dir);
  const StageCache cache(dir.string());
  ParamSet p = default_params(find_scene_type("particles"));
  int computed = 0;
  std::vector<uint8_t> restored;
  const std::vector<std::string> keyed = {"particles.seed", "particles.count"};
  auto make_graph = [&](StageGraph& g) {
    g.add_input("particles.seed");
    g.add_stage("table", {"particles.seed"}, [&] {
      return std::make_unique<CachedStage>(
          cache, [&] { return StageCache::key("table", 1, p, keyed); },
          [&] {
            ++computed;
            return std::vector<uint8_t>{1, 2, 3, uint8_t(p.get_int("particles.seed"))};
          },
          [&](std::span<const uint8_t> b) { restored.assign(b.begin(), b.end()); });
    });
  };
  const std::vector<std::string> targets = {"table"};
  {
    StageGraph g;  // first run: computes and stores
    make_graph(g);
    CHECK(g.update(targets).cached.empty());
    CHECK(computed == 1);
  }
  {
    StageGraph g;  // "the next run of masav": loads
    make_graph(g);
    CHECK(g.update(targets).cached == std::vector<std::string>{"table"});
    CHECK(computed == 1);
    CHECK(restored == std::vector<uint8_t>{1, 2, 3, 1});
    CHECK(g.counters("table").cache_hits == 1);
    // Another seed is another key: computed (and stored), then that one loads too.
    p.set("particles.seed", int64_t(9));
    g.touch("particles.seed");
    CHECK(g.update(targets).cached.empty());
    CHECK(computed == 2);
  }
  // A damaged file is a miss, never an error.
  const std::string k = StageCache::key("table", 1, p, keyed);
  {
    std::ofstream out(cache.path_of(k), std::ios::binary | std::ios::trunc);
    out << "MASAVSC1 truncated";
  }
  CHECK_FALSE(cache.load(k).has_value());
  CHECK(cache.store(k, std::vector<uint8_t>{7}));
  CHECK(cache.load(k) == std::vector<uint8_t>{7});
  CHECK_FALSE(cache.load(k + " other").has_value());
  std::string why;
  CHECK_FALSE(StageCache("/proc/masav").store(k, std::vector<uint8_t>{1}, &why));
  CHECK(why.find("cannot write") != std::string::npos);
  fs::remove_all(dir);
}

TEST_CASE("the particle scene reruns only what a change needs and never creates the rest") {
  cpu::CpuBackend cpu(2);
  ParamSet p = default_params(find_scene_type("particles"));
  p.set("particles.count", int64_t(3000));
  p.set("particles.grid_cells", int64_t(8));
  p.set("render.width", int64_t(64));
  p.set("render.height", int64_t(48));
  auto s = find_scene_type("particles").create(cpu, p);
  FrameClock clock;
  UpdateReport r = s->update(clock);
  CHECK(r.ran == std::vector<std::string>{"start_uniforms", "direction_uniforms", "drift_points",
                                          "hash_grid", "reorder", "neighbor_counts", "stars"});
  // The same frame again: nothing runs.
  r = s->update(clock);
  CHECK(r.ran.empty());
  CHECK(r.skipped.size() == 7);
  // Time moves: the drift and everything downstream, not the sampling or the stars.
  clock.time_s = 0.5;
  r = s->update(clock);
  CHECK(r.ran ==
        std::vector<std::string>{"drift_points", "hash_grid", "reorder", "neighbor_counts"});
  // The view and the look of the frame are not inputs of any stage.
  s->set("camera.view", std::string("top"));
  s->set("camera.yaw_deg", 80.0);
  s->set("render.colormap", std::string("inferno"));
  s->set("render.point_size", 6.0);
  CHECK(s->update(clock).ran.empty());
  // The search radius: only the count.
  s->set("particles.neighbor_radius", 0.5);
  CHECK(s->update(clock).ran == std::vector<std::string>{"neighbor_counts"});
  // The seed: sampling and everything after it, and the stars.
  s->set("particles.seed", int64_t(2));
  CHECK(s->update(clock).ran.size() == 7);
  // Colour by speed: the grid stages are no longer reached (nor skipped).
  s->set("particles.color_by", std::string("speed"));
  const uint64_t grid_skips = s->graph().counters("hash_grid").skips;
  clock.time_s = 1.0;
  r = s->update(clock);
  CHECK(r.ran == std::vector<std::string>{"drift_points"});
  CHECK(s->graph().counters("hash_grid").skips == grid_skips);
  CHECK(s->view().points->from == PointLayer::ScalarFrom::position_w);

  // A scene that never colours by neighbours never creates the grid, and one on black never
  // creates the star field: no buffers, no kernels, so no pipelines.
  ParamSet q = p;
  q.set("particles.color_by", std::string("height"));
  q.set("render.background", std::string("black"));
  auto t = find_scene_type("particles").create(cpu, q);
  for (double time : {0.0, 0.1, 0.2}) {
    clock.time_s = time;
    t->update(clock);
  }
  for (const char* never : {"hash_grid", "reorder", "neighbor_counts", "stars"}) {
    CAPTURE(never);
    CHECK_FALSE(t->graph().created(never));
    CHECK(t->graph().counters(never).runs == 0);
  }
  CHECK(t->graph().counters("drift_points").runs == 3);
  CHECK(t->graph().counters("start_uniforms").runs == 1);
  CHECK(t->graph().counters("start_uniforms").skips == 2);
  CHECK_FALSE(t->view().background.has_value());
}

TEST_CASE("the view input changes with the camera and only with it") {
  cpu::CpuBackend cpu(1);
  ParamSet p = default_params(find_scene_type("particles"));
  p.set("particles.count", int64_t(500));
  auto s = find_scene_type("particles").create(cpu, p);
  // A stage as the atom scene's viewer attenuation would be: it reads only "view".
  int runs = 0;
  s->graph().add_stage("viewer", {"view"},
                       [&] { return std::make_unique<LambdaStage>([&] { ++runs; }); });
  const std::vector<std::string> viewer = {"viewer"};
  FrameClock clock;
  s->update(clock);
  s->graph().update(viewer);
  CHECK(runs == 1);
  s->set("render.colormap", std::string("grey"));
  s->set("particles.drift_speed", 0.2);
  clock.time_s = 1.0;  // the camera does not turn: time is not a view change
  s->update(clock);
  s->graph().update(viewer);
  CHECK(runs == 1);
  s->set("camera.yaw_deg", 10.0);
  s->graph().update(viewer);
  CHECK(runs == 2);
  s->set("camera.orbit_speed_deg", 30.0);  // a turning camera: every new time is a new view
  s->graph().update(viewer);
  CHECK(runs == 3);
  clock.time_s = 2.0;
  s->update(clock);
  s->graph().update(viewer);
  CHECK(runs == 4);
  s->update(clock);  // the same time: no change
  s->graph().update(viewer);
  CHECK(runs == 4);
}

TEST_CASE("cross-parameter limits of the particle scene name the parameters and the remedy") {
  cpu::CpuBackend cpu(1);
  ParamSet p = default_params(find_scene_type("particles"));
  p.set("particles.count", int64_t(4000000));
  p.set("particles.grid_cells", int64_t(8));
  const std::string e = error_of([&] { find_scene_type("particles").create(cpu, p); });
  CHECK(e.find("particles.count = 4000000") != std::string::npos);
  CHECK(e.find("particles.grid_cells >=") != std::string::npos);
  // Changing a parameter into the same trap is refused and keeps the old value.
  p.set("particles.count", int64_t(1000));
  auto s = find_scene_type("particles").create(cpu, p);
  CHECK_THROWS_AS(s->set("particles.count", int64_t(4000000)), Error);
  CHECK(s->params().get_int("particles.count") == 1000);
}

TEST_CASE("the cross-check passes on agreeing backends and catches every kind of mismatch") {
  cpu::CpuBackend a(2), b(1);
  ParamSet p = default_params(find_scene_type("particles"));
  p.set("particles.count", int64_t(5000));
  const verify::CrossCheckReport ok = verify::cross_check_scene(a, b, p);
  CHECK(ok.pass());
  CHECK(ok.rows.size() == 7);
  CHECK(ok.points == 5000);
  const std::string json = verify::report_json(ok);
  CHECK(json.find("\"kernel\": \"drift_points\"") != std::string::npos);
  CHECK(json.find("\"pass\": true") != std::string::npos);
  CHECK(verify::format_report(ok).find("7 of 7 kernels agree") != std::string::npos);

  // Broken comparisons: a kernel that answers differently on one of the two backends.
  const CheckInputs in = find_scene_type("particles").check_inputs(p);
  auto differs = [&a](Backend& be) { return &be == &a; };
  std::vector<verify::KernelCheck> broken = {
      verify::exact_check("exact_kernel",
                          [&](Backend& be, const CheckInputs&) {
                            std::vector<uint32_t> w(100, 7);
                            if (differs(be)) w[42] = 8;
                            return verify::CheckOutputs{{"words", w, {}}};
                          }),
      verify::tolerance_check("float_kernel", {1e-6, 1e-6, 1e-6, 1e-9},
                              [&](Backend& be, const CheckInputs&) {
                                std::vector<double> v(100, 1.0);
                                if (differs(be)) v[3] = 1.001;
                                return verify::CheckOutputs{{"values", {}, v}};
                              }),
      verify::chi_square_check("statistical_kernel", 1e-3,
                               [&](Backend& be, const CheckInputs&) {
                                 std::vector<double> h = {1000, 1000, 1000, 1000};
                                 if (differs(be)) h = {1300, 900, 900, 900};
                                 return verify::CheckOutputs{{"histogram", {}, h}};
                               }),
  };
  const verify::CrossCheckReport bad = verify::cross_check(
      a, b, {"exact_kernel", "float_kernel", "statistical_kernel", "unchecked_kernel"}, in, broken);
  CHECK(bad.failures() == 4);
  CHECK(bad.rows[0].metrics.find("1 of 100 words differ (first: words[42] = 8 against 7)") !=
        std::string::npos);
  CHECK(bad.rows[1].numbers.at("max_abs") == doctest::Approx(0.001));
  CHECK(bad.rows[2].numbers.at("p_value") < 1e-3);
  CHECK(bad.rows[3].error.find("no cross-check") != std::string::npos);
  CHECK(verify::failure_summary(bad).find("exact_kernel, float_kernel") != std::string::npos);

  // The same checks pass when the backends agree (the checks themselves are sound).
  const verify::CrossCheckReport fine =
      verify::cross_check(b, b, {"exact_kernel", "float_kernel", "statistical_kernel"}, in, broken);
  CHECK(fine.pass());
}

TEST_CASE("an injected fault perturbs one kernel's output and the cross-check catches it") {
  cpu::CpuBackend a(1), b(1);
  ParamSet p = default_params(find_scene_type("particles"));
  p.set("particles.count", int64_t(2000));
  for (const char* kernel : {"drift_points", "grid_count_neighbors", "philox_uniform"}) {
    CAPTURE(kernel);
    const verify::CrossCheckReport r = verify::cross_check_scene(a, b, p, find_kernel(kernel));
    CHECK(r.failures() == 1);
    for (const auto& row : r.rows) CHECK(row.pass == (row.kernel != kernel));
  }
}

TEST_CASE("chi-square p-values match closed forms") {
  // Q(1, x) = exp(-x); with 2 degrees of freedom p = exp(-chi2 / 2).
  for (double x : {0.1, 1.0, 3.0, 12.0}) CHECK(gamma_q(1.0, x) == doctest::Approx(std::exp(-x)));
  // Q(1/2, x) = erfc(sqrt(x)).
  for (double x : {0.2, 2.0, 8.0})
    CHECK(gamma_q(0.5, x) == doctest::Approx(std::erfc(std::sqrt(x))));
  const std::vector<double> a = {10, 20, 30}, b = {10, 20, 30};
  const ChiSquare same = chi_square_two_sample(a, b);
  CHECK(same.statistic == 0);
  CHECK(same.p_value == doctest::Approx(1.0));
  CHECK(same.dof == 2);
}

TEST_CASE("every kernel of kernels.inc has a built-in cross-check") {
  for (KernelId k : kAllKernels) {
    CAPTURE(kernel_name(k));
    CHECK(verify::find_kernel_check(k) != nullptr);
  }
  // And every built-in check belongs to a kernel.
  for (const auto& c : verify::kernel_checks()) CHECK_MESSAGE(find_kernel(c.kernel), c.kernel);
}
