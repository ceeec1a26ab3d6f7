#pragma once
// A 1,000-particle dam break, 24 steps in blocks of 8, on a given backend: the run behind the
// tests that a choice keeps the trajectory (the neighbour state, sph.neighbor_state; RK4's reach
// masks against the walk of the inflated cells, SphSimulation::drop_reach_masks).
#include <doctest/doctest.h>

#include "engine/sph/sph_presets.h"
#include "engine/sph/sph_simulation.h"
#include "tests/backend_fixture.h"

namespace masav::test {

struct SwitchRun {
  SphState state;
  bool reach_masks = false;     // SphSimulation::keeps_reach_masks()
  bool neighbor_state = false;  // SphSimulation::keeps_neighbor_state()
};

inline SwitchRun run_dam_break_on(Backend& b, SphIntegrator integrator, bool drop_reach = false) {
  SphScene s = make_preset("dam-break", 1000);
  s.integrator = integrator;
  SphSimulation sim(b, s);
  if (drop_reach) sim.drop_reach_masks();
  sim.set_block_steps(8);
  CHECK(sim.run(24) == 24);
  return {sim.download(), sim.keeps_reach_masks(), sim.keeps_neighbor_state()};
}

}  // namespace masav::test
