// SphScheme's commits and the choice of a scene's scheme.
#include "engine/sph/sph_scheme.h"

#include <fmt/format.h>

#include <utility>

#include "engine/core/error.h"
#include "engine/sph/sph_device_state.h"
#include "engine/sph/sph_dfsph_scheme.h"
#include "engine/sph/sph_ranks.h"

namespace masav {

void SphScheme::commit_rebuilt() {
  SphDeviceState& d = c_.device;
  if (c_.ranks) c_.ranks->commit();
  std::swap(d.pos, d.ta);
  std::swap(d.vel, d.tb);
  std::swap(d.ids, d.ids_t);
  c_.progress.accel_valid = true;
  c_.progress.fields_current = true;  // the force pass ran at the new positions
}

void SphScheme::commit_stage() {
  SphDeviceState& d = c_.device;
  std::swap(d.pos, d.xs);
  std::swap(d.vel, d.vs);
}

std::unique_ptr<SphScheme> make_sph_scheme(const SphContext& c) {
  if (c.dfsph()) return std::make_unique<SphDfsphScheme>(c);
  switch (c.scene.integrator) {
    case SphIntegrator::euler:
      return make_euler_scheme(c, SphStageOp::euler);
    case SphIntegrator::symplectic_euler:
      return make_euler_scheme(c, SphStageOp::symplectic_euler);
    case SphIntegrator::rk4:
      return make_rk4_scheme(c);
    case SphIntegrator::leapfrog:
      return make_leapfrog_scheme(c);
  }
  throw Error("sph", "integrator",
              fmt::format("no scheme for integrator {}", int(c.scene.integrator)),
              "internal error: validate(SphScene) accepts only the integrators above");
}

}  // namespace masav
