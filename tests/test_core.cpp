// Backend-independent pieces: the shared math headers (what the CPU reference and CUDA call),
// errors, the registry's answers to bad names, the thread pool, JSON and atomic files.
#define DOCTEST_CONFIG_IMPLEMENT_WITH_MAIN
#include <doctest/doctest.h>

#include <atomic>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>

#include "engine/core/error.h"
#include "engine/cpu/thread_pool.h"
#include "engine/io/csv_writer.h"
#include "engine/io/vtk_writer.h"
#include "engine/kernels/grid_cell.h"
#include "engine/kernels/grid_params.h"
#include "engine/kernels/philox.h"
#include "engine/kernels/radix.h"
#include "engine/util/error_metrics.h"
#include "engine/util/json_writer.h"
#include "registry/backends.h"

using namespace masav;

TEST_CASE("philox header reproduces the Random123 known answers") {
  auto a = philox::philox4x32_10({{0, 0, 0, 0}}, 0, 0);
  CHECK(a.w[0] == 0x6627e8d5u);
  CHECK(a.w[3] == 0x9b00dbd8u);
  auto b = philox::philox4x32_10({{~0u, ~0u, ~0u, ~0u}}, ~0u, ~0u);
  CHECK(b.w[0] == 0x408f276du);
  CHECK(b.w[1] == 0x41c83b0eu);
  CHECK(b.w[2] == 0xa20bc7c6u);
  CHECK(b.w[3] == 0x6d5451fdu);
  auto c = philox::philox4x32_10({{0x243f6a88u, 0x85a308d3u, 0x13198a2eu, 0x03707344u}},
                                 0xa4093822u, 0x299f31d0u);
  CHECK(c.w[0] == 0xd16cfe09u);
  CHECK(c.w[1] == 0x94fdccebu);
  CHECK(c.w[2] == 0x5001e420u);
  CHECK(c.w[3] == 0x24126ea1u);
}

TEST_CASE("uniform floats are exact shifts into [0, 1)") {
  CHECK(philox::u01(0) == 0.0f);
  CHECK(philox::u01(~0u) == 1.0f - 1.0f / 16777216.0f);
  CHECK(philox::u01(0x80000000u) == 0.5f);
}

TEST_CASE("grid cell math clamps, handles faces and NaN") {
  CHECK(grid::axis_cell(0.0f, 0.0f, 10.0f, 5) == 0);
  CHECK(grid::axis_cell(0.1f, 0.0f, 10.0f, 5) == 1);  // 0.1f * 10 rounds to exactly 1
  CHECK(grid::axis_cell(-3.0f, 0.0f, 10.0f, 5) == 0);
  CHECK(grid::axis_cell(99.0f, 0.0f, 10.0f, 5) == 4);
  CHECK(grid::axis_cell(std::numeric_limits<float>::quiet_NaN(), 0.0f, 10.0f, 5) == 0);
  CHECK(grid::axis_cell(std::numeric_limits<float>::infinity(), 0.0f, 10.0f, 5) == 4);
  CHECK(grid::cell_id(1, 2, 3, 10, 100) == (1 * 10 + 2) * 100 + 3);
  const GridParams g = make_grid_params({0, 0, 0}, 0.5f, {1000, 3, 1}, 0);
  CHECK(grid_cell_count(g) == 3000);
  CHECK(grid_key_bits(g) == 12);
  CHECK(grid_key_bits(make_grid_params({0, 0, 0}, 1, {1, 1, 1}, 0)) == 1);
}

TEST_CASE("neighbour walk visits the 27 cells in x-major order, clipped to the grid") {
  const uint32_t dims[3] = {3, 3, 3};
  uint32_t start[27], end[27];
  for (uint32_t i = 0; i < 27; ++i) start[i] = i, end[i] = i + 1;
  std::vector<uint32_t> seen;
  grid::for_each_neighbor_cell({1, 1, 1}, dims, start, end,
                               [&](uint32_t a, uint32_t) { seen.push_back(a); });
  REQUIRE(seen.size() == 27);
  for (uint32_t i = 0; i < 27; ++i) CHECK(seen[i] == i);
  seen.clear();
  grid::for_each_neighbor_cell({0, 0, 0}, dims, start, end,
                               [&](uint32_t a, uint32_t) { seen.push_back(a); });
  CHECK(seen == std::vector<uint32_t>{0, 1, 3, 4, 9, 10, 12, 13});
}

TEST_CASE("radix pass arithmetic") {
  CHECK(radix::pass_count(32) == 4);
  CHECK(radix::pass_count(17) == 3);
  CHECK(radix::pass_bits(17, 2) == 1);
  CHECK(radix::pass_count(1) == 1);
  CHECK(radix::digit(0xABCD1234u, 8, 8) == 0x12u);
  CHECK(radix::digit(0xABCD1234u, 16, 4) == 0xDu);
  // Every pass writes another buffer than it reads, and the last lands home unless there is one.
  for (uint32_t passes = 1; passes <= 6; ++passes) {
    CAPTURE(passes);
    radix::PassBuffer src = radix::PassBuffer::home;
    bool b_used = false;
    for (uint32_t pass = 0; pass < passes; ++pass) {
      const radix::PassBuffer dst = radix::pass_buffer(passes, pass);
      CHECK(dst != src);
      b_used = b_used || dst == radix::PassBuffer::b;
      src = dst;
    }
    CHECK((src == radix::PassBuffer::home) == (passes > 1));
    CHECK(b_used == radix::uses_second_scratch(passes));
  }
}

TEST_CASE("errors name the place, the problem and the remedy") {
  const Error e("vulkan", "radix_sort", "too big", "use fewer");
  CHECK(std::string(e.what()) == "vulkan/radix_sort: too big (remedy: use fewer)");
  CHECK_THROWS_WITH_AS(throw_invalid("bench", "--n", "0", "in [1, 2^28]"),
                       "bench: invalid --n = 0 (remedy: --n must be in [1, 2^28])", Error);
}

TEST_CASE("registry rejects unknown backends and lists all three") {
  CHECK_THROWS_WITH_AS(create_backend("metal"), doctest::Contains("one of vulkan, cuda, cpu, auto"),
                       Error);
  const auto all = list_backends();
  REQUIRE(all.size() == 3);
  bool cpu_ok = false;
  for (const auto& s : all) {
    if (!s.available) CHECK(!s.reason.empty());  // every unavailable backend says why
    if (s.name == "cpu") cpu_ok = s.available;
  }
  CHECK(cpu_ok);
  CHECK_THROWS_WITH_AS(create_backend("cpu", "3"), doctest::Contains("device"), Error);
}

TEST_CASE("thread pool runs chunks in order of position and propagates exceptions") {
  cpu::ThreadPool pool(4);
  std::vector<int> owner(1000, -1);
  pool.run_chunks(1000, 7, [&](size_t c, size_t b, size_t e) {
    for (size_t i = b; i < e; ++i) owner[i] = int(c);
  });
  for (size_t i = 1; i < owner.size(); ++i) CHECK(owner[i] >= owner[i - 1]);
  CHECK(owner.front() == 0);
  CHECK(owner.back() == 6);
  std::atomic<size_t> sum{0};
  pool.parallel_for(100000, 100, [&](size_t b, size_t e) { sum += e - b; });
  CHECK(sum == 100000);
  CHECK_THROWS_AS(pool.parallel_for(100, 1,
                                    [](size_t b, size_t) {
                                      if (b == 0) throw std::runtime_error("boom");
                                    }),
                  std::runtime_error);
}

TEST_CASE("JSON writer nests and escapes; files are written atomically") {
  JsonWriter j;
  j.begin_object().field("name", "a\"b").field("n", 3).key("list").begin_array();
  j.value(1.5).value(true).end_array().key("empty").begin_object().end_object().end_object();
  CHECK(j.str() ==
        "{\n  \"name\": \"a\\\"b\",\n  \"n\": 3,\n  \"list\": [\n    1.5,\n    true\n  ],\n"
        "  \"empty\": {}\n}");
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / "masav_test_atomic";
  fs::remove_all(dir);
  write_file_atomic((dir / "sub" / "x.json").string(), j.str());
  std::ifstream in(dir / "sub" / "x.json");
  std::string text((std::istreambuf_iterator<char>(in)), {});
  CHECK(text == j.str());
  size_t files = 0;
  for (const auto& e : fs::directory_iterator(dir / "sub")) (void)e, ++files;
  CHECK(files == 1);  // no temporary left behind
  CHECK_THROWS_WITH_AS(write_file_atomic("/proc/masav/forbidden.json", "x"),
                       doctest::Contains("cannot write"), Error);
  fs::remove_all(dir);
}

TEST_CASE("error metrics: max abs, max rel with a floor, relative L2") {
  const std::vector<double> want = {1.0, 2.0, 0.0, -4.0};
  const std::vector<double> got = {1.0, 2.2, 1e-9, -4.0};
  const ErrorStats e = compare(std::span<const double>(got), std::span<const double>(want), 1e-6);
  CHECK(e.max_abs == doctest::Approx(0.2));
  CHECK(e.max_rel == doctest::Approx(0.1));
  CHECK(e.worst == 1);
  CHECK(e.rel_l2 == doctest::Approx(0.2 / std::sqrt(21.0)).epsilon(1e-6));
  const std::vector<double> bad = {NAN, 2.0, 0.0, -4.0};
  CHECK(compare(std::span<const double>(bad), std::span<const double>(want), 1e-6).non_finite == 1);
}

TEST_CASE("VTK writer: base64 and well-formed PolyData / ImageData") {
  CHECK(base64("Man", 3) == "TWFu");
  CHECK(base64("Ma", 2) == "TWE=");
  CHECK(base64("M", 1) == "TQ==");
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / "masav_test_vtk";
  fs::remove_all(dir);
  write_vtp((dir / "p.vtp").string(), {0, 0, 0, 1, 2, 3}, {{"density", 1, {1000.f, 998.f}}});
  std::ifstream in(dir / "p.vtp");
  std::string text((std::istreambuf_iterator<char>(in)), {});
  CHECK(text.find("NumberOfPoints=\"2\"") != std::string::npos);
  CHECK(text.find("Name=\"density\"") != std::string::npos);
  const uint32_t dims[3] = {2, 2, 1};
  const double origin[3] = {0, 0, 0}, spacing[3] = {1, 1, 1};
  write_vti((dir / "v.vti").string(), dims, origin, spacing, {{"p", 1, {0.f, 1.f, 2.f, 3.f}}});
  CHECK(fs::exists(dir / "v.vti"));
  CHECK_THROWS_AS(write_vtp((dir / "bad.vtp").string(), {0, 0, 0}, {{"x", 1, {1.f, 2.f}}}), Error);
  fs::remove_all(dir);
}

TEST_CASE("CSV rows quote text and refuse ragged rows") {
  CsvWriter csv({"t", "label"});
  csv.row_text({"0.5", "a,b"});
  CHECK(csv.str() == "t,label\n0.5,\"a,b\"\n");
  CHECK_THROWS_AS(csv.row({1.0}), Error);
}
