#pragma once
// A 1,000-particle dam break on the backend under test, 24 steps in blocks of 8, with one
// environment switch read when the simulation is built (set for that, restored after): the run
// behind the tests that a switch keeps the trajectory (MASAV_SPH_REACH, MASAV_SPH_NEIGHBOR_STATE).
#include <doctest/doctest.h>

#include <optional>

#include "engine/sph/sph_presets.h"
#include "engine/sph/sph_simulation.h"
#include "tests/backend_fixture.h"
#include "tests/scoped_env.h"

namespace masav::test {

struct SwitchRun {
  SphState state;
  bool reach_masks = false;     // SphSimulation::keeps_reach_masks()
  bool neighbor_state = false;  // SphSimulation::keeps_neighbor_state()
};

inline SwitchRun run_dam_break_with(SphIntegrator integrator, const char* name, const char* value) {
  SphScene s = make_preset("dam-break", 1000);
  s.integrator = integrator;
  std::optional<SphSimulation> sim;
  {
    const ScopedEnv env(name, value);
    sim.emplace(backend(), s);
  }
  sim->set_block_steps(8);
  CHECK(sim->run(24) == 24);
  return {sim->download(), sim->keeps_reach_masks(), sim->keeps_neighbor_state()};
}

}  // namespace masav::test
