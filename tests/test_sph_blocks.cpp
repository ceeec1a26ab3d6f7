// SphSimulation::run's blocks (one stats read per block, a checkpoint to replay from) against
// step-by-step runs, on every backend: the same state bit for bit at a fixed dt, and a guard
// that stops at the same step with the same message when the trouble starts inside a block.
// Blocks captured as units (Vulkan replays, CUDA graphs) against the same blocks uncaptured.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "engine/core/error.h"
#include "engine/sph/sph_presets.h"
#include "engine/sph/sph_simulation.h"
#include "registry/backends.h"
#include "tests/backend_fixture.h"
#include "tests/sph_state_compare.h"

using namespace masav;

namespace {

struct Outcome {
  SphState state;
  std::string error;  // empty: the run finished
  uint64_t steps = 0, substeps = 0, replays = 0;
  uint64_t graphs = 0;        // work queued as one unit (DeviceApi::begin_capture)
  uint64_t graph_builds = 0;  // of it, the units built (the others reused one)
  double time = 0;
};

// Vulkan replays each block's recording unless vulkan.replay=off; CUDA captures each block as
// a graph where cuda.graphs=on (and not with cuda.sync_each_launch).
bool captures_blocks(const Backend& b) {
  const Tuning& t = b.tuning();
  if (b.name() == "vulkan") return resolve(t.vulkan.replay, true);
  return b.name() == "cuda" && resolve(t.cuda.graphs, false) && !t.cuda.sync_each_launch;
}

Outcome run_in_blocks(const SphScene& s, uint32_t block, uint64_t steps,
                      Backend& b = test::backend()) {
  SphSimulation sim(b, s);
  sim.set_block_steps(block);
  const uint64_t graphs0 = b.counters().graphs, builds0 = b.counters().graph_builds;
  Outcome o;
  try {
    const uint64_t taken = sim.run(steps);
    CHECK(taken == steps);
  } catch (const Error& e) {
    o.error = e.what();
  }
  o.state = sim.download();
  o.steps = sim.steps();
  o.substeps = sim.substeps();
  o.replays = sim.block_replays();
  o.time = sim.time();
  o.graphs = b.counters().graphs - graphs0;
  o.graph_builds = b.counters().graph_builds - builds0;
  return o;
}

// The backend under test created again with its captures off (Vulkan: no replays; CUDA: no
// graphs).
std::unique_ptr<Backend> backend_without_captures() {
  Tuning t = test::tuning();
  t.vulkan.replay = Choice::off;
  t.cuda.graphs = Choice::off;
  try {
    return test::backend_with(t);
  } catch (...) {
    return nullptr;
  }
}

}  // namespace

TEST_CASE("[sph-physics] run() in blocks gives the step-by-step state bit for bit") {
  for (SphIntegrator integ : {SphIntegrator::euler, SphIntegrator::leapfrog, SphIntegrator::rk4}) {
    const std::string name = to_string(integ);
    CAPTURE(name);
    SphScene s = make_preset("dam-break", 1000);
    s.integrator = integ;
    s.dt = 2e-4;
    // 20 steps: blocks of 8, 8 and 4 against 20 single steps.
    const Outcome blocks = run_in_blocks(s, 8, 20), single = run_in_blocks(s, 1, 20);
    REQUIRE(blocks.error.empty());
    REQUIRE(single.error.empty());
    CHECK(blocks.replays == 0);
    CHECK(blocks.steps == 20);
    CHECK(blocks.time == single.time);
    CHECK(test::same_state(blocks.state, single.state));
    // Captured, the blocks ran as units (CUDA graphs: the first may split where its scratch
    // memory grows; the last, of another shape, replaces the executable graph; Vulkan: the
    // blocks use the two checkpoints in turn, and the last is shorter), single steps never.
    CHECK(single.graphs == 0);
    if (captures_blocks(test::backend()))
      CHECK(blocks.graphs >= 2);
    else
      CHECK(blocks.graphs == 0);
  }
}

TEST_CASE("[sph-physics] blocks at the adaptive dt: captured units reused, bit for bit") {
  // Every block has another dt: Vulkan passes it through its replay table, CUDA updates the
  // graph. Either way the run must give what the same backend gives without captures.
  SphScene s = make_preset("dam-break", 1000);
  const Outcome captured = run_in_blocks(s, 8, 64);
  REQUIRE(captured.error.empty());
  if (!captures_blocks(test::backend())) {
    MESSAGE("skipped: " << test::backend_name() << " does not capture blocks here");
    CHECK(captured.graphs == 0);
    return;
  }
  // 8 blocks, at most half of them built (Vulkan builds 3: the first, with leapfrog's first
  // evaluation, and the first of each checkpoint slot; CUDA instantiates where a graph's shape
  // changes), the others reusing one with their own dt.
  CHECK(captured.graphs >= 8);
  CHECK(captured.graph_builds * 2 <= captured.graphs);
  const std::unique_ptr<Backend> plain = backend_without_captures();
  REQUIRE(plain);
  const Outcome direct = run_in_blocks(s, 8, 64, *plain);
  REQUIRE(direct.error.empty());
  CHECK(direct.graphs == 0);
  CHECK(captured.time == direct.time);
  CHECK(test::same_state(captured.state, direct.state));
}

TEST_CASE("[sph-physics] a block the guard rejects is replayed and stops at the very step") {
  // A fixed dt just below the explosion's initial CFL limit: the expanding gas speeds up until
  // the guard (stop) refuses step 7 (limit 0.7% under dt), inside the block of steps 1..8.
  SphScene s = make_preset("explosion", 1000);
  s.dt = 4.35e-4;
  s.cfl_guard = SphCflGuard::stop;
  const Outcome single = run_in_blocks(s, 1, 200), blocks = run_in_blocks(s, 8, 200);
  REQUIRE_FALSE(single.error.empty());
  CHECK(single.error.find("exceeds the CFL limit") != std::string::npos);
  CHECK(single.steps % 8 != 0);  // the stop falls inside a block
  CHECK(blocks.error == single.error);
  CHECK(blocks.steps == single.steps);
  CHECK(blocks.replays >= 1);
  CHECK(test::same_state(blocks.state, single.state));  // the last good state, as step by step
}

TEST_CASE("[sph-physics] a NaN entering a block is named by step and particle") {
  SphScene s = make_preset("water", 1000);
  SphSimulation sim(test::backend(), s);
  sim.set_block_steps(8);
  sim.run(3);
  SphState st = sim.download();
  st.velocities[123].x = std::nan("");
  sim.set_velocities(st.velocities);
  CHECK_THROWS_WITH_AS(sim.run(8), doctest::Contains("step 4"), Error);
  CHECK(sim.block_replays() == 1);
  CHECK_THROWS_WITH_AS(sim.run(8), doctest::Contains("particle 123 entered the step"), Error);
  CHECK(sim.steps() == 3);  // the last good state is kept
}

TEST_CASE("[sph-physics] blocks with the adaptive dt keep to the CFL limit") {
  SphScene s = make_preset("dam-break", 1000);
  const Outcome blocks = run_in_blocks(s, 8, 64), single = run_in_blocks(s, 1, 64);
  REQUIRE(blocks.error.empty());
  CHECK(blocks.steps == 64);
  // The block's dt comes from the stats before it: the run covers about the same time.
  CHECK(blocks.time == doctest::Approx(single.time).epsilon(0.1));
  SphSimulation sim(test::backend(), s);
  CHECK_THROWS_WITH_AS(sim.set_block_steps(0), doctest::Contains("1 to 64"), Error);
  CHECK_THROWS_WITH_AS(sim.set_block_steps(65), doctest::Contains("block steps"), Error);
}

TEST_CASE("[sph-physics] run() split anywhere gives the trajectory of one call bit for bit") {
  // The adaptive dt is chosen per block of the fixed schedule: calls of 3, 5, 1, ... steps (a
  // CSV row or a snapshot between them) must not move the blocks, and a resume state taken in
  // the middle of a block must continue it.
  SphScene s = make_preset("dam-break", 1000);
  const Outcome whole = run_in_blocks(s, 8, 60);
  REQUIRE(whole.error.empty());
  SphSimulation sim(test::backend(), s);
  sim.set_block_steps(8);
  uint64_t done = 0;
  for (const uint64_t part : {3u, 5u, 1u, 7u, 2u, 2u, 11u}) {
    CHECK(sim.run(part) == part);
    done += part;
  }
  REQUIRE(done == 31);  // inside the block of steps 25..32
  const SphResumeState mid = sim.export_resume_state();
  CHECK(mid.block_stats.size() == kSphStatWords);
  SphSimulation resumed(test::backend(), s);
  resumed.restore_resume_state(mid);
  for (SphSimulation* x : {&sim, &resumed}) {
    CHECK(x->run(4) == 4);
    CHECK(x->run(25) == 25);
    CHECK(x->time() == whole.time);
    CHECK(x->last_dt() > 0);
    CHECK(test::same_state(x->download(), whole.state));
  }
}

TEST_CASE("[sph-physics] reading the state inside a block leaves the trajectory alone") {
  // download() evaluates density at the current positions where the fields are stale, which
  // runs kernels that write the stats words: the open block's stats (the next block's dt) must
  // survive it. The explosion slows down and speeds up again at the walls, so a block's maxima
  // are not simply its last step's. (Without replays; the next case has them.)
  for (SphIntegrator integ : {SphIntegrator::symplectic_euler, SphIntegrator::leapfrog}) {
    const std::string name = to_string(integ);
    CAPTURE(name);
    SphScene s = make_preset("explosion", 800);
    s.integrator = integ;
    const Outcome whole = run_in_blocks(s, 8, 150);
    REQUIRE(whole.error.empty());
    REQUIRE(whole.replays == 0);
    SphSimulation sim(test::backend(), s);
    sim.set_block_steps(8);
    for (int k = 0; k < 50; ++k) {
      CHECK(sim.run(3) == 3);
      (void)sim.download();
    }
    CHECK(sim.block_replays() == 0);
    CHECK(sim.time() == whole.time);
    CHECK(test::same_state(sim.download(), whole.state));
  }
}

TEST_CASE("[sph-physics] blocks the guard rejects end at the same step however run() is split") {
  // The thesis model's water at the adaptive dt: the guard rejects blocks, and each rejection
  // must end its block at the step where a run of one step per call (a CSV row every step)
  // ends it, whether run() took the block whole, in calls of one step, or in calls of 3, 5, ...
  // with the state read between them. Every integrator; the replays are counted so the case
  // cannot pass without any.
  uint64_t replays = 0;
  for (SphIntegrator integ : {SphIntegrator::euler, SphIntegrator::symplectic_euler,
                              SphIntegrator::leapfrog, SphIntegrator::rk4}) {
    const std::string name = to_string(integ);
    CAPTURE(name);
    SphScene s = make_preset("water", 1000);
    s.model = SphPressureModel::thesis;
    s.integrator = integ;
    const Outcome whole = run_in_blocks(s, 8, 120);
    REQUIRE(whole.error.empty());
    replays += whole.replays;
    SphSimulation single(test::backend(), s), uneven(test::backend(), s);
    for (SphSimulation* x : {&single, &uneven}) x->set_block_steps(8);
    for (int k = 0; k < 120; ++k) REQUIRE(single.run(1) == 1);
    for (uint64_t done = 0, k = 0; done < 120; ++k) {
      const uint64_t part = std::min<uint64_t>(120 - done, 1 + (k * 3) % 7);
      REQUIRE(uneven.run(part) == part);
      (void)uneven.download();
      done += part;
    }
    for (SphSimulation* x : {&single, &uneven}) {
      CHECK(x->block_replays() == whole.replays);
      CHECK(x->time() == whole.time);
      CHECK(test::same_state(x->download(), whole.state));
    }
  }
  CHECK(replays > 0);
}

TEST_CASE("[sph-physics] run() takes each block's stats while the next block runs") {
  // Sixteen blocks of 8 steps, the energy watchdog's check due at step 128 among them: the host
  // waits for the device at most once, at the end of run(); every other block's stats, and the
  // state the check reads, are taken while a later block is queued (DeviceApi::read_async), and
  // nothing else travels between host and device. Leapfrog's step ends with the fields at its
  // positions; Euler's does not, so its check evaluates them first, with the steps' own kernel
  // forms: nothing is compiled mid-run (on lavapipe a form of its own stalled the host ~0.1 s).
  for (SphIntegrator integ : {SphIntegrator::leapfrog, SphIntegrator::euler}) {
    const std::string name = to_string(integ);
    CAPTURE(name);
    // A backend of its own: the suite's shared one may have built the other forms already.
    const std::unique_ptr<Backend> fresh = test::backend_with(test::tuning());
    Backend& b = *fresh;
    SphScene scene = make_preset("water", 1000);
    scene.integrator = integ;
    SphSimulation sim(b, scene);
    sim.set_block_steps(8);
    REQUIRE(sim.run(8) == 8);
    b.finish();
    b.reset_counters();
    CHECK(sim.run(128) == 128);
    const DeviceCounters& c = b.counters();
    const size_t real = b.real_bytes();
    const size_t state = 1000 * (3 * 4 * real + 2 * real + 4);  // positions, velocities, ..., ids
    CHECK(c.bytes_to_device == 0);
    CHECK(c.bytes_to_host == 16 * kSphStatWords * sizeof(uint32_t) + state);
    if (b.name() == "cpu") {
      CHECK(c.async_reads == 0);  // its work is done when recorded
    } else {
      // The one wait, at the end of run(), is no sync where the device has finished by the
      // time the host takes the last read (a GPU runs these 1,000 particles' block faster than
      // the host records the next).
      CHECK(c.host_syncs <= 1);
      CHECK(c.async_reads >= 15);
    }
    CHECK(c.pipelines_built == 0);
    CHECK(sim.block_replays() == 0);
    CHECK(sim.export_resume_state().next_energy_check == 256);  // the check at step 128 passed
  }
}
