// Checkpoints of an SPH run (engine/sph/sph_checkpoint.h), on every backend: a run continued
// from a checkpoint in a fresh simulation reaches the uninterrupted run's state bit for bit,
// for every integrator and dfsph (its warm-started solves), and damaged or foreign files are
// refused with an error naming the file, the field and what was expected.
#include <doctest/doctest.h>
#include <fmt/format.h>

#include <cstring>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "engine/core/error.h"
#include "engine/sph/sph_checkpoint.h"
#include "engine/sph/sph_presets.h"
#include "engine/sph/sph_simulation.h"
#include "tests/backend_fixture.h"
#include "tests/temp_dir.h"

using namespace masav;

namespace {

struct End {
  SphState state;
  double time = 0, last_dt = 0;
  uint64_t steps = 0, substeps = 0;
};

End end_of(SphSimulation& sim) {
  return {sim.download(), sim.time(), sim.last_dt(), sim.steps(), sim.substeps()};
}

void check_same(const End& a, const End& b) {
  CHECK(a.time == b.time);
  CHECK(a.last_dt == b.last_dt);
  CHECK(a.steps == b.steps);
  CHECK(a.substeps == b.substeps);
  REQUIRE(a.state.positions.size() == b.state.positions.size());
  size_t differ = 0;
  for (size_t i = 0; i < a.state.positions.size(); ++i) {
    const Vec4d &p = a.state.positions[i], &q = b.state.positions[i];
    const Vec4d &v = a.state.velocities[i], &w = b.state.velocities[i];
    if (p.x != q.x || p.y != q.y || p.z != q.z || v.x != w.x || v.y != w.y || v.z != w.z ||
        a.state.density[i] != b.state.density[i] || a.state.pressure[i] != b.state.pressure[i])
      ++differ;
  }
  CHECK(differ == 0);
}

std::vector<char> read_bytes(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
}

void write_bytes(const std::string& path, const std::vector<char>& b) {
  std::ofstream f(path, std::ios::binary | std::ios::trunc);
  f.write(b.data(), std::streamsize(b.size()));
}

// Where each section's header starts (see the format in sph_checkpoint.h).
std::vector<size_t> section_offsets(const std::vector<char>& b) {
  uint32_t writer = 0;
  std::memcpy(&writer, b.data() + 16, 4);
  std::vector<size_t> at;
  size_t off = 20 + writer;
  for (int i = 0; i < 3; ++i) {
    at.push_back(off);
    uint64_t bytes = 0;
    std::memcpy(&bytes, b.data() + off + 8, 8);
    off += 24 + bytes;
  }
  return at;
}

std::string read_error(const std::string& path) {
  try {
    read_sph_checkpoint(path);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

bool has(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

}  // namespace

TEST_CASE("[sph-physics] a run continued from a checkpoint reaches the same state bit for bit") {
  test::TempDir dir("sph_checkpoint_resume");
  struct Case {
    SphIntegrator integrator;
    SphPressureModel model;
  };
  for (const Case c : {Case{SphIntegrator::euler, SphPressureModel::wcsph},
                       Case{SphIntegrator::leapfrog, SphPressureModel::wcsph},
                       Case{SphIntegrator::rk4, SphPressureModel::wcsph},
                       Case{SphIntegrator::symplectic_euler, SphPressureModel::dfsph}}) {
    const std::string name =
        std::string(to_string(c.integrator)) + " / " + std::string(to_string(c.model));
    CAPTURE(name);
    SphScene s = make_preset("dam-break", 1000);
    s.integrator = c.integrator;
    s.model = c.model;  // the adaptive dt: it depends on the stats carried between steps
    // 2 x 16 steps in run()'s blocks of 8 (dfsph: one step at a time), against 32 in one go.
    SphSimulation straight(test::backend(), s);
    REQUIRE(straight.run(32) == 32);
    const End want = end_of(straight);

    const std::string path = dir.file("checkpoint.masav");
    {
      SphSimulation first(test::backend(), s);
      REQUIRE(first.run(16) == 16);
      write_sph_checkpoint(path, first);
    }
    const SphCheckpoint c0 = read_sph_checkpoint(path);
    CHECK(sph_scene_difference(c0.scene, s).empty());
    SphSimulation resumed(test::backend(), c0.scene);
    restore_sph_checkpoint(resumed, c0, path);
    CHECK(resumed.steps() == 16);
    REQUIRE(resumed.run(16) == 16);
    check_same(end_of(resumed), want);
    if (c.model == SphPressureModel::dfsph) {
      CHECK(resumed.solve_stats().density_iterations == straight.solve_stats().density_iterations);
      CHECK(resumed.solve_stats().divergence_iterations ==
            straight.solve_stats().divergence_iterations);
    }
  }
}

TEST_CASE("[sph-physics] a checkpoint written mid-run leaves the run's own trajectory alone") {
  // Writing reads the state back only: the run that wrote it goes on as if it had not.
  SphScene s = make_preset("dam-break", 1000);
  s.integrator = SphIntegrator::leapfrog;
  test::TempDir dir("sph_checkpoint_inert");
  SphSimulation a(test::backend(), s), b(test::backend(), s);
  a.run(8);
  b.run(8);
  write_sph_checkpoint(dir.file("c.masav"), b);
  a.run(8);
  b.run(8);
  check_same(end_of(b), end_of(a));
}

TEST_CASE("sph checkpoint: damaged, foreign and mismatched files are refused, naming the field") {
  test::TempDir dir("sph_checkpoint_errors");
  const SphScene s = make_preset("water", 300);
  SphSimulation sim(test::backend(), s);
  sim.run(3);
  const std::string good = dir.file("good.masav");
  write_sph_checkpoint(good, sim);
  const std::vector<char> bytes = read_bytes(good);
  const std::vector<size_t> at = section_offsets(bytes);
  const std::string bad = dir.file("bad.masav");
  CHECK(read_error(good).empty());

  SUBCASE("a flipped byte: the section's checksum") {
    std::vector<char> b = bytes;
    b[at[2] + 24 + 100] ^= 0x10;  // inside PART's payload
    write_bytes(bad, b);
    const std::string e = read_error(bad);
    CHECK(has(e, bad));
    CHECK(has(e, "PART section: checksum mismatch"));
  }
  SUBCASE("truncated") {
    write_bytes(bad, std::vector<char>(bytes.begin(), bytes.begin() + bytes.size() / 2));
    const std::string e = read_error(bad);
    CHECK(has(e, bad));
    CHECK(has(e, "PART section: needs"));
    CHECK(has(e, "truncated"));
    write_bytes(bad, std::vector<char>(bytes.begin(), bytes.begin() + 10));
    CHECK(has(read_error(bad), "header: needs 16 bytes, the file has 10 left"));
    write_bytes(bad, {});
    CHECK(has(read_error(bad), "header: needs"));
  }
  SUBCASE("wrong magic") {
    std::vector<char> b = bytes;
    b[0] = 'X';
    write_bytes(bad, b);
    CHECK(has(read_error(bad), "magic: not a masav SPH checkpoint"));
  }
  SUBCASE("a newer format version") {
    std::vector<char> b = bytes;
    const uint32_t v = kSphCheckpointVersion + 1;
    std::memcpy(b.data() + 8, &v, 4);
    write_bytes(bad, b);
    const std::string e = read_error(bad);
    CHECK(has(e, fmt::format("format version: {}", v)));
    CHECK(has(e, "written by a newer masav"));
  }
  SUBCASE("2^40 particles claimed (checksum intact): refused before allocating") {
    std::vector<char> b = bytes;
    const uint64_t n = uint64_t(1) << 40;
    std::memcpy(b.data() + at[1] + 24, &n, 8);  // STAT's first field
    uint64_t stat_bytes = 0;
    std::memcpy(&stat_bytes, b.data() + at[1] + 8, 8);
    const uint64_t sum = fnv1a64(std::span<const uint8_t>(
        reinterpret_cast<const uint8_t*>(b.data() + at[1] + 24), size_t(stat_bytes)));
    std::memcpy(b.data() + at[1] + 16, &sum, 8);
    write_bytes(bad, b);
    CHECK(has(read_error(bad), "STAT.particles: 1099511627776 where 1 to 1073741824"));
    const uint64_t more = 300 * 1000;  // within the bound, beyond what PART holds
    std::memcpy(b.data() + at[1] + 24, &more, 8);
    const uint64_t sum2 = fnv1a64(std::span<const uint8_t>(
        reinterpret_cast<const uint8_t*>(b.data() + at[1] + 24), size_t(stat_bytes)));
    std::memcpy(b.data() + at[1] + 16, &sum2, 8);
    write_bytes(bad, b);
    CHECK(has(read_error(bad), "STAT.particles: 300000 particles need more than"));
  }
  SUBCASE("a scene of more fluid particles than the file holds") {
    std::vector<char> b = bytes;
    const size_t payload = at[0] + 24;
    uint32_t preset = 0;  // the preset's name comes first, then the fluid particle count
    std::memcpy(&preset, b.data() + payload, 4);
    const uint32_t more = 301;
    std::memcpy(b.data() + payload + 4 + preset, &more, 4);
    uint64_t scene_bytes = 0;
    std::memcpy(&scene_bytes, b.data() + at[0] + 8, 8);
    const uint64_t sum = fnv1a64(std::span<const uint8_t>(
        reinterpret_cast<const uint8_t*>(b.data() + payload), size_t(scene_bytes)));
    std::memcpy(b.data() + at[0] + 16, &sum, 8);
    write_bytes(bad, b);
    CHECK(has(read_error(bad), "SCEN.particles: 301 fluid particles where STAT holds 300"));
  }
  SUBCASE("a missing file") {
    CHECK(has(read_error(dir.file("none.masav")), "cannot open"));
  }
  SUBCASE("another scene, another particle count") {
    const SphCheckpoint c = read_sph_checkpoint(good);
    SphScene other = s;
    other.viscosity *= 2;
    SphSimulation o(test::backend(), other);
    try {
      restore_sph_checkpoint(o, c, good);
      FAIL("restored into another scene");
    } catch (const Error& e) {
      CHECK(has(e.what(), "SCEN.viscosity: differs"));
    }
    SphSimulation bigger(test::backend(), make_preset("water", 500));
    try {
      restore_sph_checkpoint(bigger, c, good);
      FAIL("restored into another particle count");
    } catch (const Error& e) {
      CHECK(has(e.what(), "SCEN.particles: differs"));
    }
    SphResumeState r = c.state;
    r.positions.pop_back();
    CHECK_THROWS_WITH_AS(sim.restore_resume_state(r), doctest::Contains("positions = 299 values"),
                         Error);
    r = c.state;
    r.ids[0] = r.ids[1];
    CHECK_THROWS_WITH_AS(sim.restore_resume_state(r), doctest::Contains("each of 0 to"), Error);
  }
}
