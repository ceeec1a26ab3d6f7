// SphSimulation, the facade: its parts built in order and the simulation's first state (the
// initial particles, a first force pass for the first dt, the watchdog's baseline), the velocity
// replacement, and the accessors that depend on the scheme. The resume state is in
// sph_simulation_resume.cpp.
#include "engine/sph/sph_simulation.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "engine/core/error.h"
#include "engine/kernels/kernel_checks.h"
#include "engine/sph/sph_dfsph_scheme.h"

namespace masav {
namespace {

int rank_count(const SphComm* comm) {
  return comm ? comm->size() : 1;
}

const SphScene& validated(const SphScene& scene) {
  validate(scene);
  return scene;
}

// The scene's particles, refused before they are built where the device cannot hold the fluid,
// and once built where it cannot hold them with the obstacle's.
SphParticles checked_particles(const Backend& backend, const SphScene& scene, int ranks) {
  SphDeviceState::check_capacity(backend, scene, ranks);
  SphParticles layout = build_particles(scene);
  SphDeviceState::check_buffer_size(backend, layout.total(), ranks);
  return layout;
}

std::unique_ptr<SphRanks> make_ranks(SphComm* comm, Backend& backend, const GridParams& grid) {
  if (rank_count(comm) <= 1) return nullptr;
  return std::make_unique<SphRanks>(*comm, backend, grid);
}

}  // namespace

SphSimulation::SphSimulation(Backend& backend, const SphScene& scene, SphComm* comm)
    : backend_(backend),
      scene_(validated(scene)),
      layout_(checked_particles(backend, scene_, rank_count(comm))),
      grid_shape_(sph_grid_shape(scene_, layout_)),
      ranks_(make_ranks(comm, backend, grid_shape_.params)),
      device_(backend, scene_, layout_.total(), rank_count(comm)),
      fields_(backend, scene_, layout_, grid_shape_, device_, ranks_.get(), device_.capacity()),
      context_{backend, scene_, layout_, ranks_.get(), device_, fields_, progress_},
      scheme_(make_sph_scheme(context_)),
      dfsph_(dynamic_cast<SphDfsphScheme*>(scheme_.get())),
      reads_(context_),
      watch_(context_, *this),
      control_(context_, *scheme_, watch_, reads_),
      blocks_(context_, control_, reads_, watch_) {
  // Beyond the initial capacity, a rank's buffers grow before it takes more particles.
  if (ranks_)
    ranks_->on_reserve([this](uint32_t local) { device_.reserve(local, fields_.grid()); });
  device_.allocate();
  const uint32_t n = layout_.total();
  if (ranks_) {
    ranks_->scatter_by_id(layout_.positions, layout_.velocities, true, device_.pos, device_.vel,
                          device_.ids);
  } else {
    backend_.upload(device_.pos, layout_.positions);
    backend_.upload(device_.vel, layout_.velocities);
    std::vector<uint32_t> ids(n);
    for (uint32_t i = 0; i < n; ++i) ids[i] = i;
    backend_.upload(device_.ids, ids);
  }

  // A first force pass gives a_max for the first dt (and leapfrog's first kick).
  fields_.clear_stats();
  fields_.sort_state();
  fields_.evaluate(device_.pos, device_.vel);
  uint32_t w[kSphStatWords];
  SphProgress& p = progress_;
  p.stats = fields_.read_stats(w);
  if (w[kSphStatOverflow] != 0)
    throw Error(backend_.name(), "sph",
                fmt::format("a particle of the initial state has more than {} neighbour "
                            "candidates in its 27 cells",
                            scene_.max_candidates),
                fmt::format("raise max_candidates (at most {}) or lower the initial density_ratio",
                            max_sph_candidates(kPortableLoopBudget)));
  double vmax = 0;
  for (const auto& v : layout_.velocities) vmax = std::max(vmax, std::hypot(v.x, v.y, v.z));
  p.stats.max_speed = vmax;
  p.lag_stats = p.stats;
  p.accel_valid = !context_.dfsph();  // dfsph's first step adds its factor
  p.fields_current = true;
  p.adaptive_dt = std::min(scene_.dt_max, dt_limit());
  const SphState s0 = download();
  watch_.start(s0, p.stats.max_density);
}

void SphSimulation::step() {
  control_.step();
}

uint64_t SphSimulation::run(uint64_t steps, double t_end) {
  return blocks_.run(steps, t_end);
}

const SphSolveStats& SphSimulation::solve_stats() const {
  static const SphSolveStats none;  // the other models run no solves
  return dfsph_ ? dfsph_->solve_stats() : none;
}

uint64_t SphSimulation::dfsph_residual_reads() const {
  return dfsph_ ? dfsph_->residual_reads() : 0;
}

void SphSimulation::set_dfsph_queued_iterations(bool on) {
  if (dfsph_) dfsph_->set_queued_iterations(on);
}

void SphSimulation::set_velocities(const std::vector<Vec4d>& by_id) {
  const uint32_t n = layout_.total();
  if (by_id.size() != n)
    throw_invalid("sph", "velocities", std::to_string(by_id.size()),
                  fmt::format("one per particle ({})", n));
  const std::vector<uint32_t> ids = backend_.download(device_.ids);
  std::vector<Vec4d> vel = backend_.download(device_.vel);
  // The own particles' (on several ranks), or all.
  const uint32_t first = ranks_ ? ranks_->committed().first : 0;
  const uint32_t end = ranks_ ? first + ranks_->committed().own : n;
  for (uint32_t i = first; i < end; ++i) vel[i] = by_id[ids[i]];
  backend_.upload(device_.vel, vel);
  progress_.accel_valid = false;
  progress_.fields_current = false;
  double vmax = 0;
  for (const auto& v : by_id) vmax = std::max(vmax, std::hypot(v.x, v.y, v.z));
  if (std::isfinite(vmax)) {
    progress_.stats.max_speed = std::max(progress_.stats.max_speed, vmax);
    progress_.lag_stats.max_speed = std::max(progress_.lag_stats.max_speed, vmax);
    // Energy the caller adds is the new baseline; speeds up to twice the fastest given are legal.
    SphWatchdog& bounds = watch_.bounds();
    bounds.max_speed = std::max(bounds.max_speed, 2 * vmax);
    watch_.set_baseline(download());
  }
}

}  // namespace masav
