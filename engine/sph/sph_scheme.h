#pragma once
// One integrator of the SPH simulation: the kernels of one step of dt from the committed state
// (SphDeviceState, in the order of the last rebuild), and the commit that makes the step's
// results the state. The step control (sph_step_control.h) judges the step's stats between the
// two, the block scheduler (sph_block_scheduler.h) records several before it reads any.
//
// Each scheme has its own file: Euler and symplectic Euler (sph_euler_scheme.cpp), leapfrog
// (sph_leapfrog_scheme.cpp), RK4 (sph_rk4_scheme.cpp) and the dfsph pressure model, which
// brings its own integrator (sph_dfsph_scheme.h).
#include <memory>

#include "engine/sph/sph_context.h"

namespace masav {

class SphScheme {
 public:
  explicit SphScheme(const SphContext& c) : c_(c) {}
  virtual ~SphScheme() = default;
  SphScheme(const SphScheme&) = delete;
  SphScheme& operator=(const SphScheme&) = delete;

  // The step's kernels, into the scratch arrays; the committed state stays as it is.
  virtual void record(double dt) = 0;
  // The recorded step's arrays become the committed state (swaps, no kernel).
  virtual void commit() = 0;

 protected:
  // The commit of a step that ends with a rebuild (leapfrog, dfsph): the rebuild's arrays and
  // its layout on several ranks become the state, with the force pass run at it.
  void commit_rebuilt();
  // The commit of a step that ends in the stage arrays xs, vs (Euler, RK4).
  void commit_stage();

  SphContext c_;
};

// The scheme of `c.scene` (its integrator, or dfsph's own for that pressure model).
std::unique_ptr<SphScheme> make_sph_scheme(const SphContext& c);

// The schemes of the integrators (their files); make_sph_scheme chooses.
std::unique_ptr<SphScheme> make_euler_scheme(const SphContext& c, SphStageOp op);
std::unique_ptr<SphScheme> make_leapfrog_scheme(const SphContext& c);
std::unique_ptr<SphScheme> make_rk4_scheme(const SphContext& c);

}  // namespace masav
