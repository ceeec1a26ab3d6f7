#include "engine/sph/sph_simulation.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <span>
#include <string>

#include "engine/core/enum_names.h"
#include "engine/core/error.h"
#include "engine/kernels/kernel_checks.h"
#include "engine/sph/sph_coefficients.h"
#include "engine/sph/sph_kernel_calls.h"

namespace masav {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr int kMaxRetries = 12;

float bits_to_float(uint32_t w) {
  return std::bit_cast<float>(w);
}

}  // namespace

const char* to_string(SphStage s) {
  static const char* const names[] = {"grid", "density", "forces", "integrate", "solve"};
  return enum_name(s, names);
}

SphSimulation::SphSimulation(Backend& backend, const SphScene& scene, SphComm* comm)
    : backend_(backend), scene_(scene) {
  validate(scene_);
  const int ranks = comm ? comm->size() : 1;
  check_capacity(backend_, scene_, ranks);
  layout_ = build_particles(scene_);
  n_ = layout_.total();
  check_buffer_size(backend_, n_, ranks);  // with the obstacle's particles
  capacity_ = initial_capacity(n_, ranks);

  // The grid: cells of h (Euler, leapfrog) or h (1 + skin) (RK4) over the box.
  const double h = layout_.h;
  skin_ = scene_.integrator == SphIntegrator::rk4 ? scene_.rk4_skin * h : 0.0;
  cell_size_ = h + skin_;
  // fp32 cell size, rounded up so that it is never below h + skin in fp32 either.
  float cell = float(cell_size_);
  if (double(cell) < cell_size_) cell = std::nextafter(cell, 2.0f * cell);
  const double ext[3] = {scene_.box_max.x - scene_.box_min.x, scene_.box_max.y - scene_.box_min.y,
                         scene_.box_max.z - scene_.box_min.z};
  uint32_t dims[3];
  for (int a = 0; a < 3; ++a) {
    const double cells = std::ceil(ext[a] / double(cell));
    if (cells > double(1 << 20))
      throw_invalid("sph scene", "box", fmt::format("{} m on axis {}", ext[a], a),
                    fmt::format("at most 2^20 cells of {} m per axis; shrink the box or use "
                                "fewer particles",
                                cell));
    dims[a] = std::max(1u, uint32_t(cells));
  }
  const GridParams gp =
      make_grid_params({float(scene_.box_min.x), float(scene_.box_min.y), float(scene_.box_min.z)},
                       cell, {dims[0], dims[1], dims[2]}, n_);
  if (grid_cell_count(gp) > (uint64_t(1) << 27))
    throw_invalid("sph scene", "box", fmt::format("{} x {} x {} cells", dims[0], dims[1], dims[2]),
                  "at most 2^27 grid cells (box / smoothing radius); shrink the box or use a "
                  "larger smoothing radius");

  step_params_.grid = gp;
  step_params_.n = n_;
  step_params_.max_candidates = scene_.max_candidates;
  step_params_.model = scene_.model;
  step_params_.h = h;
  step_params_.mass = layout_.mass;
  step_params_.gradient_correction = layout_.gradient_correction;
  step_params_.rest_density = scene_.rest_density;
  step_params_.sound_speed = scene_.sound_speed;
  step_params_.clamp_negative_pressure = scene_.clamp_negative_pressure;
  step_params_.kp = scene_.kp;
  step_params_.viscosity = scene_.viscosity;
  step_params_.gravity = scene_.gravity;
  step_params_.walls = scene_.walls;
  step_params_.box_min = scene_.box_min;
  step_params_.box_max = scene_.box_max;

  if (ranks > 1) {
    ranks_ = std::make_unique<SphRanks>(*comm, backend_, gp);
    ranks_->on_reserve([this](uint32_t local) { reserve(local); });  // beyond initial_capacity
  }
  GridParams local_grid = gp;  // on several ranks the rank layout sets n before any build
  local_grid.n = std::min(gp.n, capacity_);
  grid_ = make_hash_grid(backend_, local_grid, capacity_);
  stats_buf_ = backend_.create<uint32_t>(kSphStatWords, "sph stats");
  allocate_particle_buffers();

  if (ranks_) {
    ranks_->scatter_by_id(layout_.positions, layout_.velocities, true, pos_, vel_, ids_);
  } else {
    backend_.upload(pos_, layout_.positions);
    backend_.upload(vel_, layout_.velocities);
    std::vector<uint32_t> ids(n_);
    for (uint32_t i = 0; i < n_; ++i) ids[i] = i;
    backend_.upload(ids_, ids);
  }

  // A first force pass gives a_max for the first dt (and leapfrog's first kick).
  backend_.fill(stats_buf_, 0u);
  sort_state();
  evaluate(pos_, vel_);
  uint32_t w[kSphStatWords];
  stats_ = read_stats(w);
  if (w[kSphStatOverflow] != 0)
    throw Error(backend_.name(), "sph",
                fmt::format("a particle of the initial state has more than {} neighbour "
                            "candidates in its 27 cells",
                            scene_.max_candidates),
                fmt::format("raise max_candidates (at most {}) or lower the initial density_ratio",
                            max_sph_candidates(kPortableLoopBudget)));
  double vmax = 0;
  for (const auto& v : layout_.velocities) vmax = std::max(vmax, std::hypot(v.x, v.y, v.z));
  stats_.max_speed = vmax;
  lag_stats_ = stats_;
  accel_valid_ = !dfsph();  // dfsph's first step adds its factor
  fields_current_ = true;
  adaptive_dt_ = std::min(scene_.dt_max, dt_limit());
  const SphState s0 = download();
  watchdog_ = make_watchdog(s0, *this, stats_.max_density);
  set_watchdog_baseline(s0);
}

// Forward Euler multiplies the energy of every undamped oscillation by 1 + (omega dt)^2 per
// step, and a fluid's sound waves are such oscillations: at the others' Courant number a dam
// break doubles its energy within 400 steps (512 particles), at half of it still gains 27%, at
// a quarter it loses energy as the viscosity and walls take it. So Euler steps are 4x shorter.
// dfsph has no speed of sound in its limit, only the flow's: its Courant number is halved, to
// dt = 0.1 h / v_max = 0.2 dx / v_max at h = 2 dx (SPlisHSPlasH's default). The solves then
// take fewer iterations per step, and the density the particles reach stays closer to what the
// density solve predicted (dam break, 4,096 particles: mean compression 0.03% rather than 0.1%,
// about the same iterations per simulated second).
double SphSimulation::courant_scale() const {
  if (dfsph()) return 0.5;
  return scene_.integrator == SphIntegrator::euler ? 0.25 : 1.0;
}

double SphSimulation::limit_for(const SphStepStats& s) const {
  const double h = layout_.h;
  const double c = signal_speed(step_params_);
  const double k = courant_scale();
  double dt = k * scene_.cfl_velocity * h / (c + s.max_speed);
  if (s.max_accel > 0) dt = std::min(dt, k * scene_.cfl_force * std::sqrt(h / s.max_accel));
  if (scene_.viscosity > 0) dt = std::min(dt, scene_.cfl_viscous * h * h / scene_.viscosity);
  if (skin_ > 0 && s.max_speed > 0) dt = std::min(dt, 0.5 * 0.5 * skin_ / s.max_speed);
  return dt;
}

double SphSimulation::dt_limit() const {
  return limit_for(stats_);
}

void SphSimulation::mark(SphStage ended) {
  if (profiling_) marks_.push_back({backend_.timestamp(), ended});
}

// The rebuild on `x` (the counting build; a particle's own cell is among its candidates, so a
// cell fuller than max_candidates is an overflow of the SPH kernels anyway), with x, v and ids
// moved into cell order by its rank pass (x_sorted, v_sorted, ids_sorted).
void SphSimulation::rebuild_moving(const Buffer<Real4>& x, Buffer<Real4>& x_sorted,
                                   const Buffer<Real4>& v, Buffer<Real4>& v_sorted,
                                   const Buffer<uint32_t>& ids, Buffer<uint32_t>& ids_sorted) {
  build_hash_grid_moving(backend_, grid_, x, scene_.max_candidates,
                         MovedArrays{&x_sorted, &v, &v_sorted, &ids, &ids_sorted});
}

void SphSimulation::use_rank_layout(const Buffer<Real4>& x) {
  const SphRankLayout& l = ranks_->staged();
  grid_.params.n = l.local;
  step_params_.grid.n = l.local;
  step_params_.n = l.local;
  step_params_.first = l.first;
  step_params_.count = l.own;
  // The arrays are in cell order already: this build only marks the cells' ranges (its sort
  // keeps the order, being stable).
  build_hash_grid(backend_, grid_, x, {GridBuild::counting, scene_.max_candidates});
}

void SphSimulation::sort_state() {
  // dfsph's kappa sums (its warm starts, in pos_'s order) move with the particles.
  const std::array<SphCarried, 2> kappa_sums = {SphCarried{kappa_density_, kappa_density_t_},
                                                SphCarried{kappa_divergence_, kappa_divergence_t_}};
  const std::span<const SphCarried> carried(kappa_sums.data(), dfsph() ? 2 : 0);
  if (ranks_) {
    ranks_->redistribute(pos_, vel_, ids_, carried, ta_, tb_, ids_t_);
    ranks_->commit();
    use_rank_layout(ta_);
  } else {
    rebuild_moving(pos_, ta_, vel_, tb_, ids_, ids_t_);
    for (const SphCarried& c : carried) reorder(backend_, grid_, c.from(), c.to());
  }
  std::swap(pos_, ta_);
  std::swap(vel_, tb_);
  std::swap(ids_, ids_t_);
  if (dfsph()) {
    std::swap(kappa_density_, kappa_density_t_);
    std::swap(kappa_divergence_, kappa_divergence_t_);
  }
  mark(SphStage::grid);
}

Buffer<uint32_t>* SphSimulation::neighbor_rows() {
  return neighbor_rows_.valid() ? &neighbor_rows_ : nullptr;
}

SphDensityIO SphSimulation::density_io(const Buffer<Real4>& x, const Buffer<Real4>& v) {
  SphDensityIO io{&x, sph_grid_view(grid_), &density_, &pressure_, &stats_buf_, neighbor_rows()};
  // The neighbour state is kept in one process only (neighbor_state_fits).
  if (neighbor_state_.valid()) {
    io.velocities = &v;
    io.neighbor_state = &neighbor_state_;
  }
  return io;
}

SphForcesIO SphSimulation::forces_io(const Buffer<Real4>& x, const Buffer<Real4>& v) {
  SphForcesIO io{&x,      &v,          &density_,      &pressure_, sph_grid_view(grid_),
                 &accel_, &stats_buf_, neighbor_rows()};
  if (neighbor_state_.valid()) io.neighbor_state = &neighbor_state_;
  return io;
}

void SphSimulation::evaluate(const Buffer<Real4>& x, const Buffer<Real4>& v, SphReach reach) {
  SphStepParams density_params = step_params_;
  SphDensityIO density = density_io(x, v);
  if (reach != SphReach::none && reach_rows_.valid()) {
    density_params.reach = reach;
    density_params.reach_radius = double(step_params_.grid.cell_size);
    density.reach_rows = &reach_rows_;
  }
  sph_density(backend_, density_params, density);
  mark(SphStage::density);
  const SphForcesIO forces = forces_io(x, v);
  if (!ranks_) {
    sph_forces(backend_, step_params_, forces);
  } else {
    // The halos' density and pressure travel while the forces of the own particles that have
    // no halo neighbour run; then the rest of the own range (its ends).
    ranks_->start_halos(density_, pressure_);
    const auto [begin, end] = ranks_->interior();
    auto forces_over = [&](uint32_t first, uint32_t last) {
      if (first >= last) return;
      SphStepParams p = step_params_;
      p.first = first;
      p.count = last - first;
      sph_forces(backend_, p, forces);
    };
    forces_over(begin, end);
    ranks_->finish_halos();
    forces_over(step_params_.first, begin);
    forces_over(end, step_params_.first + step_params_.count);
    ranks_->count_overlapped(end - begin);
  }
  mark(SphStage::forces);
}

void SphSimulation::integrate(SphStageOp op, double dt, const Buffer<Real4>& x0,
                              const Buffer<Real4>& v0, const Buffer<Real4>* vk,
                              Buffer<Real4>* x_out, Buffer<Real4>& v_out, Buffer<Real4>* sum_x,
                              Buffer<Real4>* sum_v) {
  SphIntegrateParams p;
  p.n = n_;
  if (ranks_) {
    // kick_drift starts from the committed state; the other stages from the grid's arrays
    // (the same layout, except for leapfrog's kick after its rebuild).
    const SphRankLayout& l = op == SphStageOp::kick_drift ? ranks_->committed() : ranks_->staged();
    p.n = l.local;
    p.first = l.first;
    p.count = l.own;
  }
  p.op = op;
  p.dt = dt;
  p.walls = scene_.walls;
  // With mirror-image walls (wcsph, dfsph) the box the integrator holds particles in is a quarter
  // of a particle spacing inside the walls. A particle's own image is its strongest repulsion near
  // a wall, but it has no slope on the wall itself (the image coincides with the particle), where
  // the density it adds is largest: a particle put back exactly on the wall would sit on top of
  // that energy hill and gain what the image term then gives back. A quarter spacing in, the
  // clamp only ever moves a particle down that hill (dissipates), and the first lattice layer
  // (half a spacing in) is untouched.
  const double margin =
      scene_.walls && scene_.model != SphPressureModel::thesis ? 0.25 * layout_.dx : 0.0;
  const Vec3d &lo = scene_.box_min, &hi = scene_.box_max;
  p.box_min = {lo.x + margin, lo.y + margin, lo.z + margin};
  p.box_max = {hi.x - margin, hi.y - margin, hi.z - margin};
  p.restitution = scene_.restitution;
  p.tangential_damping = scene_.tangential_damping;
  sph_integrate(backend_, p,
                SphIntegrateIO{&x0, &v0, vk, &accel_, x_out, &v_out, sum_x, sum_v, &stats_buf_});
  mark(SphStage::integrate);
}

void SphSimulation::step_euler(double dt, SphStageOp op) {
  sort_state();
  evaluate(pos_, vel_);
  integrate(op, dt, pos_, vel_, nullptr, &xs_, vs_, nullptr, nullptr);
}

void SphSimulation::step_rk4(double dt) {
  sort_state();  // the one rebuild of this step (see the header)
  evaluate(pos_, vel_, SphReach::record);
  // On several ranks the halos' stage states come from their owners before each evaluation.
  auto stage_halos = [&] {
    if (!ranks_) return;
    ranks_->exchange_halos(xs_, vs_);
  };
  integrate(SphStageOp::rk4_stage1, dt, pos_, vel_, nullptr, &xs_, vs_, &sum_x_, &sum_v_);
  stage_halos();
  evaluate(xs_, vs_, SphReach::walk);
  integrate(SphStageOp::rk4_stage2, dt, pos_, vel_, &vs_, &xs_, vs_, &sum_x_, &sum_v_);
  stage_halos();
  evaluate(xs_, vs_, SphReach::walk);
  integrate(SphStageOp::rk4_stage3, dt, pos_, vel_, &vs_, &xs_, vs_, &sum_x_, &sum_v_);
  stage_halos();
  evaluate(xs_, vs_, SphReach::walk);
  integrate(SphStageOp::rk4_final, dt, pos_, vel_, &vs_, &xs_, vs_, &sum_x_, &sum_v_);
}

void SphSimulation::step_leapfrog(double dt) {
  if (!accel_valid_) {
    sort_state();
    evaluate(pos_, vel_);
    accel_valid_ = true;
  }
  // Kick and drift from the committed state; sum_v_ gets the predicted end velocity.
  integrate(SphStageOp::kick_drift, dt, pos_, vel_, nullptr, &xs_, vs_, nullptr, &sum_v_);
  const bool viscous = scene_.viscosity > 0;
  if (ranks_) {
    // The predicted velocities move with the particles (the halos' too).
    const SphCarried predicted[] = {{sum_v_, tc_}};
    ranks_->redistribute(xs_, vs_, ids_, std::span(predicted, viscous ? 1 : 0), ta_, tb_, ids_t_);
    use_rank_layout(ta_);
  } else {
    rebuild_moving(xs_, ta_, vs_, tb_, ids_, ids_t_);
    if (viscous) reorder(backend_, grid_, sum_v_.impl(), tc_.impl());
  }
  mark(SphStage::grid);
  // Forces at the new positions; viscosity sees the predicted end-of-step velocity, which keeps
  // the scheme second order when forces depend on velocity.
  accel_valid_ = false;
  evaluate(ta_, viscous ? tc_ : tb_);
  integrate(SphStageOp::kick, dt, tb_, tb_, nullptr, nullptr, tb_, nullptr, nullptr);
}

SphStepStats SphSimulation::read_stats(uint32_t w[kSphStatWords]) {
  const std::vector<uint32_t> words = backend_.download(stats_buf_);
  std::copy(words.begin(), words.begin() + kSphStatWords, w);
  return stats_from_words(w);
}

SphStepStats SphSimulation::stats_from_words(uint32_t w[kSphStatWords]) {
  if (ranks_) ranks_->reduce_stats(w);
  SphStepStats s;
  s.max_speed = std::sqrt(double(bits_to_float(w[kSphStatMaxSpeed2])));
  s.max_accel = std::sqrt(double(bits_to_float(w[kSphStatMaxAccel2])));
  s.max_drift = std::sqrt(double(bits_to_float(w[kSphStatMaxDisp2])));
  s.max_candidates = w[kSphStatMaxCandidates];
  s.max_neighbors = w[kSphStatMaxNeighbors];
  s.max_density = double(bits_to_float(w[kSphStatMaxDensity]));
  s.outside = w[kSphStatOutside];
  return s;
}

void SphSimulation::collect_stage_times() {
  if (!profiling_ || marks_.empty()) return;
  double prev = backend_.timestamp_ns(first_mark_);
  for (const auto& [id, stage] : marks_) {
    const double t = backend_.timestamp_ns(id);
    stage_ms_[size_t(stage)] += (t - prev) * 1e-6;
    prev = t;
  }
  marks_.clear();
}

void SphSimulation::record_step(double dt) {
  if (dfsph()) {
    step_dfsph(dt);
    fields_current_ = false;
    return;
  }
  switch (scene_.integrator) {
    case SphIntegrator::euler:
      step_euler(dt, SphStageOp::euler);
      break;
    case SphIntegrator::symplectic_euler:
      step_euler(dt, SphStageOp::symplectic_euler);
      break;
    case SphIntegrator::rk4:
      step_rk4(dt);
      break;
    case SphIntegrator::leapfrog:
      step_leapfrog(dt);
      break;
  }
  fields_current_ = false;
}

SphSimulation::Attempt SphSimulation::judge(const uint32_t w[kSphStatWords], const SphStepStats& s,
                                            double dt) const {
  Attempt a;
  if (w[kSphStatOverflow] != 0) {
    a.ok = false;
    a.overflow = true;
    a.reason = "neighbour candidates overflowed";
  } else if (w[kSphStatNonFinite] != 0) {
    a.ok = false;
    a.reason = "a position or velocity became NaN/Inf";
  } else if (skin_ > 0 && s.max_drift > 0.5 * skin_) {
    a.ok = false;
    a.reason = fmt::format(
        "an RK4 stage moved a particle {:.3g} m, more than the grid's skin / 2 "
        "= {:.3g} m",
        s.max_drift, 0.5 * skin_);
  } else if (scene_.cfl_guard != SphCflGuard::off) {
    const double courant = dt * (signal_speed(step_params_) + s.max_speed) / layout_.h;
    if (courant > 2.0 * courant_scale() * scene_.cfl_velocity) {
      a.ok = false;
      a.reason = fmt::format(
          "the Courant number reached {:.3g} (limit {:.3g}: max speed {:.3g} "
          "m/s)",
          courant, courant_scale() * scene_.cfl_velocity, s.max_speed);
    }
  }
  if (!a.ok) return a;
  if (s.max_speed > watchdog_.max_speed) {
    a.ok = false;
    a.watchdog = true;
    a.reason = fmt::format(
        "a particle reached {:.3g} m/s, above the watchdog's speed bound {:.3g} m/s (2x the "
        "largest of the speed of sound c0, the free-fall speed over the box and the initial "
        "speeds)",
        s.max_speed, watchdog_.max_speed);
  } else if (s.max_density > watchdog_.max_density) {
    a.ok = false;
    a.watchdog = true;
    a.reason = fmt::format(
        "the density reached {:.4g} kg/m^3, above the watchdog's bound {:.4g} kg/m^3 (2x the "
        "rest or initial density; 3x for the thesis model)",
        s.max_density, watchdog_.max_density);
  }
  return a;
}

void SphSimulation::commit(double dt) {
  if (dfsph()) {
    std::swap(kappa_density_, kappa_density_t_);
    std::swap(kappa_divergence_, kappa_divergence_t_);
    kappa_warm_ = true;
  }
  if (scene_.integrator == SphIntegrator::leapfrog || dfsph()) {
    if (ranks_) ranks_->commit();
    std::swap(pos_, ta_);
    std::swap(vel_, tb_);
    std::swap(ids_, ids_t_);
    accel_valid_ = true;
    fields_current_ = true;  // the force pass ran at the new positions
  } else {
    std::swap(pos_, xs_);
    std::swap(vel_, vs_);
  }
  time_ += dt;
  last_dt_ = dt;
  ++substeps_;
}

SphSimulation::Attempt SphSimulation::attempt(double dt) {
  if (profiling_) {
    backend_.finish();
    backend_.reset_timestamps();
    first_mark_ = backend_.timestamp();
  }
  backend_.fill(stats_buf_, 0u);
  record_step(dt);
  uint32_t w[kSphStatWords];
  const SphStepStats s = read_stats(w);  // waits for the step
  collect_stage_times();
  const Attempt a = judge(w, s, dt);
  if (a.overflow)
    fail_together(
        Error(backend_.name(), "sph",
              fmt::format("step {}: a particle has more than {} neighbour candidates in its 27 "
                          "cells (the fluid is compressed far beyond rest density)",
                          steps_ + 1, scene_.max_candidates),
              fmt::format("raise max_candidates (at most {}), lower dt, or stiffen the fluid "
                          "(sound_speed, kp)",
                          max_sph_candidates(kPortableLoopBudget))));
  if (a.watchdog)
    fail_together(Error(
        backend_.name(), "sph watchdog",
        fmt::format("step {} (t = {:.6g} s, dt = {:.3g} s): {}", steps_ + 1, time_, dt, a.reason),
        watchdog_remedy()));
  if (!a.ok) {
    if (scene_.integrator == SphIntegrator::leapfrog || dfsph()) accel_valid_ = false;
    return a;
  }
  commit(dt);
  stats_ = s;
  return a;
}

void SphSimulation::fail_non_finite(double dt) {
  if (ranks_) fail_non_finite_ranks(dt);
  // Name the particle: one already non-finite in the committed state (the origin), else the
  // first one the step turned non-finite.
  auto first_bad = [](const std::vector<Vec4d>& p, const std::vector<Vec4d>& v,
                      const std::vector<uint32_t>& ids) {
    uint32_t best = UINT32_MAX;
    for (size_t i = 0; i < p.size(); ++i) {
      const bool bad = !std::isfinite(p[i].x) || !std::isfinite(p[i].y) || !std::isfinite(p[i].z) ||
                       !std::isfinite(v[i].x) || !std::isfinite(v[i].y) || !std::isfinite(v[i].z);
      if (bad) best = std::min(best, ids[i]);
    }
    return best;
  };
  uint32_t id =
      first_bad(backend_.download(pos_), backend_.download(vel_), backend_.download(ids_));
  const bool origin = id != UINT32_MAX;
  if (!origin) {
    const bool lf = scene_.integrator == SphIntegrator::leapfrog || dfsph();
    id = first_bad(backend_.download(lf ? ta_ : xs_), backend_.download(lf ? tb_ : vs_),
                   backend_.download(lf ? ids_t_ : ids_));
  }
  throw_non_finite(dt, id, origin);
}

void SphSimulation::fail_together(const Error& e) {
  failed_together_ = true;
  throw e;
}

void SphSimulation::throw_non_finite(double dt, uint32_t id, bool origin) {
  fail_together(Error(
      backend_.name(), "sph",
      fmt::format("step {} (t = {:.6g} s, dt = {:.3g} s): particle {} {} a non-finite "
                  "position or velocity",
                  steps_ + 1, time_, dt, id == UINT32_MAX ? std::string("?") : std::to_string(id),
                  origin ? "entered the step with" : "got"),
      "the state of the last good step is kept (export it to inspect); lower dt or use "
      "the adaptive dt, raise viscosity, or check the scene's parameters"));
}

void SphSimulation::advance(double dt, int depth, bool whole) {
  const Attempt a = attempt(dt);
  if (a.ok) return;
  ++retries_;
  const bool non_finite = a.reason.find("NaN") != std::string::npos;
  if (scene_.cfl_guard == SphCflGuard::stop || scene_.cfl_guard == SphCflGuard::off ||
      depth >= kMaxRetries || dt * 0.5 < scene_.dt_min) {
    if (non_finite) fail_non_finite(dt);
    fail_together(
        Error(backend_.name(), "sph cfl guard",
              fmt::format("step {} (t = {:.6g} s) with dt = {:.3g} s was unstable: {}", steps_ + 1,
                          time_, dt, a.reason),
              scene_.cfl_guard == SphCflGuard::stop
                  ? fmt::format("use dt <= {:.3g} s (the CFL limit now) or the adaptive dt, "
                                "or --cfl-guard reduce to let masav split steps",
                                dt_limit())
                  : fmt::format("the guard could not stabilise it above dt_min = {:.3g} s: "
                                "lower sound_speed or kp, raise viscosity, or give the fluid "
                                "more room",
                                scene_.dt_min)));
  }
  // Retry with half the step; a fixed-dt step still covers its whole interval.
  advance(0.5 * dt, depth + 1, whole);
  if (whole) advance(0.5 * dt, depth + 1, whole);
}

void SphSimulation::step() {
  block_open_ = false;  // a step of its own ends run()'s block (its stats are reset below)
  const double limit = dt_limit();
  if (scene_.dt) {
    const double dt = *scene_.dt;
    uint64_t parts = 1;
    if (dt > limit && scene_.cfl_guard != SphCflGuard::off) {
      if (scene_.cfl_guard == SphCflGuard::stop)
        fail_together(Error(
            backend_.name(), "sph cfl guard",
            fmt::format("step {} (t = {:.6g} s): dt = {:.3g} s exceeds the CFL limit "
                        "{:.3g} s (velocity {:.3g} m/s, acceleration {:.3g} m/s^2, "
                        "signal speed {:.3g} m/s, h = {:.3g} m)",
                        steps_ + 1, time_, dt, limit, stats_.max_speed, stats_.max_accel,
                        signal_speed(step_params_), layout_.h),
            fmt::format("use dt <= {:.3g} s, the adaptive dt, or --cfl-guard reduce", limit)));
      const double want = std::ceil(dt / limit);
      if (want > double(kMaxSubsteps) || dt / want < scene_.dt_min)
        fail_together(
            Error(backend_.name(), "sph cfl guard",
                  fmt::format("step {}: dt = {:.3g} s would need {:.3g} sub-steps of the CFL "
                              "limit {:.3g} s",
                              steps_ + 1, dt, want, limit),
                  "use a smaller dt or the adaptive dt; lower sound_speed or kp"));
      parts = uint64_t(want);
    }
    for (uint64_t k = 0; k < parts; ++k) advance(dt / double(parts), 0, true);
  } else {
    const double dt = std::min({limit, adaptive_dt_ * 1.25, scene_.dt_max});
    if (dt < scene_.dt_min)
      fail_together(Error(
          backend_.name(), "sph cfl guard",
          fmt::format("step {} (t = {:.6g} s): the CFL limit {:.3g} s is below dt_min = "
                      "{:.3g} s (max speed {:.3g} m/s, max acceleration {:.3g} m/s^2)",
                      steps_ + 1, time_, dt, scene_.dt_min, stats_.max_speed, stats_.max_accel),
          "the fluid is blowing up: lower sound_speed or kp, raise viscosity"));
    advance(dt, 0, false);
    adaptive_dt_ = last_dt_;
  }
  ++steps_;
  lag_stats_ = stats_;  // a block after a step takes its limit from the step's stats
  watch_energy();
}

void SphSimulation::set_velocities(const std::vector<Vec4d>& by_id) {
  if (by_id.size() != n_)
    throw_invalid("sph", "velocities", std::to_string(by_id.size()),
                  fmt::format("one per particle ({})", n_));
  const std::vector<uint32_t> ids = backend_.download(ids_);
  std::vector<Vec4d> vel = backend_.download(vel_);
  // The own particles' (on several ranks), or all.
  const uint32_t first = ranks_ ? ranks_->committed().first : 0;
  const uint32_t end = ranks_ ? first + ranks_->committed().own : n_;
  for (uint32_t i = first; i < end; ++i) vel[i] = by_id[ids[i]];
  backend_.upload(vel_, vel);
  accel_valid_ = false;
  fields_current_ = false;
  double vmax = 0;
  for (const auto& v : by_id) vmax = std::max(vmax, std::hypot(v.x, v.y, v.z));
  if (std::isfinite(vmax)) {
    stats_.max_speed = std::max(stats_.max_speed, vmax);
    lag_stats_.max_speed = std::max(lag_stats_.max_speed, vmax);
    // Energy the caller adds is the new baseline; speeds up to twice the fastest given are legal.
    watchdog_.max_speed = std::max(watchdog_.max_speed, 2 * vmax);
    set_watchdog_baseline(download());
  }
}

}  // namespace masav
