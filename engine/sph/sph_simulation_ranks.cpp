// SphSimulation on several ranks (see the header, "Ranks"): the whole state gathered on every
// rank, and the non-finite report naming the smallest bad particle id of all ranks.
#include <fmt/format.h>

#include <cmath>
#include <cstring>

#include "engine/core/error.h"
#include "engine/sph/sph_kernel_calls.h"
#include "engine/sph/sph_simulation.h"

namespace masav {
namespace {

// One particle of the gathered state.
struct GatheredParticle {
  uint32_t id;
  double position[4], velocity[4], density, pressure, neighbors;
};

bool finite_state(const Vec4d& p, const Vec4d& v) {
  return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z) && std::isfinite(v.x) &&
         std::isfinite(v.y) && std::isfinite(v.z);
}

}  // namespace

void SphSimulation::refresh_fields_ranks() {
  if (fields_current_) return;
  // Density at the current positions: the committed state itself is re-sorted (a rebuild on
  // unchanged positions is what the next step's rebuild gives anyway) and evaluated there.
  sort_state();
  const StatsKeeper keep(*this);
  evaluate(pos_, vel_);
  accel_valid_ = false;
  fields_current_ = true;
}

SphState SphSimulation::download_own(std::vector<uint32_t>& ids) {
  if (!ranks_) {
    SphState s = download();
    ids.resize(n_);
    for (uint32_t i = 0; i < n_; ++i) ids[i] = i;
    return s;
  }
  refresh_fields_ranks();
  SphState s;
  ids = own_values(backend_, *ranks_, ids_);
  s.positions = own_values(backend_, *ranks_, pos_);
  s.velocities = own_values(backend_, *ranks_, vel_);
  s.density = own_values(backend_, *ranks_, density_);
  s.pressure = own_values(backend_, *ranks_, dfsph() ? kappa_density_ : pressure_);
  if (dfsph()) dfsph_pressure(s.pressure, s.density);
  for (const Vec4d& a : own_values(backend_, *ranks_, accel_)) s.neighbors.push_back(a.w + 1.0);
  return s;
}

SphState SphSimulation::download_ranks() {
  std::vector<uint32_t> ids;
  const SphState own = download_own(ids);
  std::vector<GatheredParticle> mine(ids.size());
  for (size_t k = 0; k < ids.size(); ++k) {
    const Vec4d &x = own.positions[k], &v = own.velocities[k];
    mine[k] = {ids[k],         {x.x, x.y, x.z, x.w}, {v.x, v.y, v.z, v.w},
               own.density[k], own.pressure[k],      own.neighbors[k]};
  }
  Bytes bytes;
  append_bytes(bytes, std::span<const GatheredParticle>(mine));
  const Bytes all = ranks_->gather(bytes);
  if (all.size() != size_t(n_) * sizeof(GatheredParticle))
    throw Error(backend_.name(), "sph ranks",
                fmt::format("the ranks hold {} bytes of particles, {} expected for {}", all.size(),
                            size_t(n_) * sizeof(GatheredParticle), n_),
                "start every rank with the same masav and the same arguments");
  SphState s = sized_state(n_);
  std::vector<bool> seen(n_, false);
  for (size_t k = 0; k < n_; ++k) {
    GatheredParticle g;
    std::memcpy(&g, all.data() + k * sizeof g, sizeof g);
    if (g.id >= n_ || seen[g.id])
      throw Error(backend_.name(), "sph ranks",
                  fmt::format("particle id {} is missing or held by two ranks", g.id),
                  "start every rank with the same masav and the same arguments");
    seen[g.id] = true;
    s.positions[g.id] = {g.position[0], g.position[1], g.position[2], g.position[3]};
    s.velocities[g.id] = {g.velocity[0], g.velocity[1], g.velocity[2], g.velocity[3]};
    s.density[g.id] = g.density;
    s.pressure[g.id] = g.pressure;
    s.neighbors[g.id] = g.neighbors;
  }
  return s;
}

void SphSimulation::fail_non_finite_ranks(double dt) {
  // As fail_non_finite: the smallest id non-finite in the committed state (the origin), else the
  // smallest the step made non-finite, over every rank's own particles.
  auto first_bad = [&](const Buffer<Real4>& p, const Buffer<Real4>& v, const Buffer<uint32_t>& id,
                       const SphRankLayout& l) {
    const auto pos = backend_.download(p);
    const auto vel = backend_.download(v);
    const auto ids = backend_.download(id);
    uint32_t best = UINT32_MAX;
    for (uint32_t i = l.first; i < l.first + l.own; ++i)
      if (!finite_state(pos[i], vel[i])) best = std::min(best, ids[i]);
    return ranks_->min(best);
  };
  uint32_t id = first_bad(pos_, vel_, ids_, ranks_->committed());
  const bool origin = id != UINT32_MAX;
  if (!origin) {
    const bool lf = scene_.integrator == SphIntegrator::leapfrog || dfsph();
    id = lf ? first_bad(ta_, tb_, ids_t_, ranks_->staged())
            : first_bad(xs_, vs_, ids_, ranks_->committed());
  }
  throw_non_finite(dt, id, origin);
}

}  // namespace masav
