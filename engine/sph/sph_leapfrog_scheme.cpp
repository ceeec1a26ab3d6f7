// Leapfrog (kick-drift-kick): the grid is rebuilt after the drift; the force pass there serves
// this step's second kick and the next step's first (one pass per step), so the step ends, like
// dfsph's, with the fields at its new positions and accel carried into the next step.
#include <memory>
#include <span>

#include "engine/sph/sph_device_state.h"
#include "engine/sph/sph_field_evaluator.h"
#include "engine/sph/sph_scheme.h"

namespace masav {
namespace {

class SphLeapfrogScheme final : public SphScheme {
 public:
  using SphScheme::SphScheme;

  void record(double dt) override {
    SphDeviceState& d = c_.device;
    SphFieldEvaluator& f = c_.fields;
    SphProgress& p = c_.progress;
    if (!p.accel_valid) {
      f.sort_state();
      f.evaluate(d.pos, d.vel);
      p.accel_valid = true;
    }
    // Kick and drift from the committed state; sum_v gets the predicted end velocity.
    f.integrate(SphStageOp::kick_drift, dt, d.pos, d.vel, nullptr, &d.xs, d.vs, nullptr, &d.sum_v);
    // The predicted velocities move with the particles (on several ranks the halos' too).
    const bool viscous = c_.scene.viscosity > 0;
    const SphCarried predicted[] = {{d.sum_v, d.tc}};
    f.rebuild_drifted(std::span(predicted, viscous ? 1 : 0));
    f.mark(SphStage::grid);
    // Forces at the new positions; viscosity sees the predicted end-of-step velocity, which
    // keeps the scheme second order when forces depend on velocity.
    p.accel_valid = false;
    f.evaluate(d.ta, viscous ? d.tc : d.tb);
    f.integrate(SphStageOp::kick, dt, d.tb, d.tb, nullptr, nullptr, d.tb, nullptr, nullptr);
  }
  void commit() override { commit_rebuilt(); }
};

}  // namespace

std::unique_ptr<SphScheme> make_leapfrog_scheme(const SphContext& c) {
  return std::make_unique<SphLeapfrogScheme>(c);
}

}  // namespace masav
