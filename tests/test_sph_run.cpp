// The SPH run object (engine/sph/sph_run.h): its outputs (CSV rows, snapshots, checkpoints, the
// last good state) and events fall on the steps they name, a run holds its directories against a
// second one, and writing them leaves the trajectory as a run without outputs takes it.
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "engine/core/error.h"
#include "engine/sph/sph_checkpoint.h"
#include "engine/sph/sph_presets.h"
#include "engine/sph/sph_run.h"
#include "tests/backend_fixture.h"
#include "tests/sph_state_compare.h"
#include "tests/temp_dir.h"

using namespace masav;

namespace {

size_t lines_of(const std::string& path) {
  std::ifstream f(path);
  size_t n = 0;
  for (std::string line; std::getline(f, line);) ++n;
  return n;
}

}  // namespace

TEST_CASE("[sph-physics] an SPH run writes its outputs on their steps and steers nothing") {
  const test::TempDir dir("sph_run");
  const SphScene scene = make_preset("dam-break", 1000);
  SphRunOptions o;
  o.steps = 40;
  o.csv = dir.file("run.csv");
  o.diag_every = 5;
  o.out_dir = dir.file("out");
  o.name = "dambreak";
  o.vtp_every = 20;
  o.checkpoint_dir = dir.file("cp");
  o.checkpoint_every = 16;
  o.progress_every = 10;
  SphRun run(o, nullptr);
  // The directories are held: a second run into them is refused, naming the option.
  CHECK_THROWS_WITH_AS(SphRun(o, nullptr), doctest::Contains("--out"), Error);

  SphSimulation sim(test::backend(), scene);
  uint64_t started = 0, progress = 0, checkpoints = 0;
  SphRunEvents events;
  events.started = [&](const SphSimulation& s) { started = s.steps() + 1; };
  events.progress = [&](const SphSimulation& s) {
    ++progress;
    CHECK(s.steps() % 10 == 0);
  };
  events.checkpoint = [&](const std::string& path, uint64_t step) {
    ++checkpoints;
    CHECK(step % 16 == 0);
    CHECK(std::filesystem::exists(path));
  };
  const SphRunResult r = run.run(sim, events);
  CHECK_FALSE(r.error);
  CHECK_FALSE(r.interrupted);
  CHECK(started == 1);
  CHECK(r.steps == 40);
  CHECK(progress == 4);
  CHECK(checkpoints == 2);
  CHECK(r.csv_rows == 9);  // step 0 and every 5th
  CHECK(lines_of(o.csv) == 10);
  for (const char* f : {"dambreak_000000.vtp", "dambreak_000020.vtp", "dambreak_000040.vtp"})
    CHECK(std::filesystem::exists(std::filesystem::path(o.out_dir) / f));
  CHECK(r.final_checkpoint == SphRun::checkpoint_path(o.checkpoint_dir));
  CHECK(read_sph_checkpoint(r.final_checkpoint).state.steps == 40);

  // The same 40 steps with no output at all reach the same state, bit for bit.
  SphSimulation plain(test::backend(), scene);
  SphRunOptions none;
  none.steps = 40;
  none.progress_every = 0;
  SphRun quiet(none, nullptr);
  CHECK(quiet.run(plain).steps == 40);
  CHECK(test::same_state(plain.download(), sim.download()));
}

TEST_CASE("an SPH run stops when asked, between its calls of the simulation, and keeps what it wrote") {
  const test::TempDir dir("sph_run_stop");
  SphRunOptions o;
  o.steps = 1000;
  o.csv = dir.file("run.csv");
  o.checkpoint_dir = dir.path.string();
  o.progress_every = 0;
  SphRun run(o, nullptr);
  SphSimulation sim(test::backend(), make_preset("water", 500));
  int polls = 0;
  SphRunEvents events;
  events.interrupted = [&] { return ++polls > 3; };
  const SphRunResult r = run.run(sim, events);
  CHECK(r.interrupted);
  CHECK(r.steps == 3);  // a CSV row every step: one step per call
  CHECK(r.csv_rows == 4);
  CHECK(read_sph_checkpoint(r.final_checkpoint).state.steps == 3);
}

TEST_CASE("an SPH run refuses snapshots without a directory") {
  SphRunOptions o;
  o.vtp_every = 10;
  CHECK_THROWS_WITH_AS(SphRun(o, nullptr), doctest::Contains("out_dir"), Error);
}
