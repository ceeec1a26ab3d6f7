// Classical RK4 with ONE grid rebuild per step, not per stage. The four stages evaluate forces
// at positions up to dt |v| away from the step start; the grid's cells are h (1 + rk4_skin)
// wide (sph_grid_shape), so a pair within h at a stage was within h + skin h of each other at
// the rebuild and lies in the 27 cells walked (each particle drifts at most skin h / 2, which
// sph_integrate measures every stage; a step that drifts further is rejected and retried with a
// smaller dt, sph_step_control.h). Rebuilding per stage would cost three more sorts and
// re-gathers of six arrays per step. The first evaluation walks the 27 inflated cells and
// records which candidates lie within h + skin (the reach masks, SphReach); the other three
// test only those, not the 27 cells' 27 / (4/3 pi) ~ 6.4 times as many (where the masks do not
// fit, every evaluation walks the cells).
#include <memory>

#include "engine/sph/sph_device_state.h"
#include "engine/sph/sph_field_evaluator.h"
#include "engine/sph/sph_ranks.h"
#include "engine/sph/sph_scheme.h"

namespace masav {
namespace {

class SphRk4Scheme final : public SphScheme {
 public:
  using SphScheme::SphScheme;

  void record(double dt) override {
    SphDeviceState& d = c_.device;
    SphFieldEvaluator& f = c_.fields;
    f.sort_state();  // the one rebuild of this step
    f.evaluate(d.pos, d.vel, SphReach::record);
    // On several ranks the halos' stage states come from their owners before each evaluation.
    auto stage_halos = [&] {
      if (!c_.ranks) return;
      c_.ranks->exchange_halos(d.xs, d.vs);
    };
    f.integrate(SphStageOp::rk4_stage1, dt, d.pos, d.vel, nullptr, &d.xs, d.vs, &d.sum_x, &d.sum_v);
    stage_halos();
    f.evaluate(d.xs, d.vs, SphReach::walk);
    f.integrate(SphStageOp::rk4_stage2, dt, d.pos, d.vel, &d.vs, &d.xs, d.vs, &d.sum_x, &d.sum_v);
    stage_halos();
    f.evaluate(d.xs, d.vs, SphReach::walk);
    f.integrate(SphStageOp::rk4_stage3, dt, d.pos, d.vel, &d.vs, &d.xs, d.vs, &d.sum_x, &d.sum_v);
    stage_halos();
    f.evaluate(d.xs, d.vs, SphReach::walk);
    f.integrate(SphStageOp::rk4_final, dt, d.pos, d.vel, &d.vs, &d.xs, d.vs, &d.sum_x, &d.sum_v);
  }
  void commit() override { commit_stage(); }
};

}  // namespace

std::unique_ptr<SphScheme> make_rk4_scheme(const SphContext& c) {
  return std::make_unique<SphRk4Scheme>(c);
}

}  // namespace masav
