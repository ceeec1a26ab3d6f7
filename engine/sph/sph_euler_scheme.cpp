// Forward Euler and symplectic Euler (SphStageOp::euler, symplectic_euler): each step rebuilds
// the grid at its start, evaluates density and forces there (one force pass per step) and
// integrates into the stage arrays.
#include <memory>

#include "engine/sph/sph_device_state.h"
#include "engine/sph/sph_field_evaluator.h"
#include "engine/sph/sph_scheme.h"

namespace masav {
namespace {

class SphEulerScheme final : public SphScheme {
 public:
  SphEulerScheme(const SphContext& c, SphStageOp op) : SphScheme(c), op_(op) {}

  void record(double dt) override {
    SphDeviceState& d = c_.device;
    SphFieldEvaluator& f = c_.fields;
    f.sort_state();
    f.evaluate(d.pos, d.vel);
    f.integrate(op_, dt, d.pos, d.vel, nullptr, &d.xs, d.vs, nullptr, nullptr);
  }
  void commit() override { commit_stage(); }

 private:
  SphStageOp op_;
};

}  // namespace

std::unique_ptr<SphScheme> make_euler_scheme(const SphContext& c, SphStageOp op) {
  return std::make_unique<SphEulerScheme>(c, op);
}

}  // namespace masav
