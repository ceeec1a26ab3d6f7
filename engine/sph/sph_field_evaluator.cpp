// SphFieldEvaluator: the grid of a scene, its rebuilds, the density, forces and integrate calls
// with the buffers each uses, the stats words and the stage timing marks.
#include "engine/sph/sph_field_evaluator.h"

#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <cmath>

#include "engine/core/enum_names.h"
#include "engine/core/error.h"
#include "engine/sph/sph_device_state.h"
#include "engine/sph/sph_kernel_calls.h"

namespace masav {
namespace {

float bits_to_float(uint32_t w) {
  return std::bit_cast<float>(w);
}

}  // namespace

const char* to_string(SphStage s) {
  static const char* const names[] = {"grid", "density", "forces", "integrate", "solve"};
  return enum_name(s, names);
}

SphGridShape sph_grid_shape(const SphScene& scene, const SphParticles& layout) {
  // The grid: cells of h (Euler, leapfrog) or h (1 + skin) (RK4) over the box.
  const double h = layout.h;
  SphGridShape shape;
  shape.skin = scene.integrator == SphIntegrator::rk4 ? scene.rk4_skin * h : 0.0;
  const double cell_size = h + shape.skin;
  // fp32 cell size, rounded up so that it is never below h + skin in fp32 either.
  float cell = float(cell_size);
  if (double(cell) < cell_size) cell = std::nextafter(cell, 2.0f * cell);
  const double ext[3] = {scene.box_max.x - scene.box_min.x, scene.box_max.y - scene.box_min.y,
                         scene.box_max.z - scene.box_min.z};
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
  shape.params =
      make_grid_params({float(scene.box_min.x), float(scene.box_min.y), float(scene.box_min.z)},
                       cell, {dims[0], dims[1], dims[2]}, layout.total());
  if (grid_cell_count(shape.params) > (uint64_t(1) << 27))
    throw_invalid("sph scene", "box", fmt::format("{} x {} x {} cells", dims[0], dims[1], dims[2]),
                  "at most 2^27 grid cells (box / smoothing radius); shrink the box or use a "
                  "larger smoothing radius");
  return shape;
}

SphFieldEvaluator::SphFieldEvaluator(Backend& backend, const SphScene& scene,
                                     const SphParticles& layout, const SphGridShape& shape,
                                     SphDeviceState& device, SphRanks* ranks, uint32_t capacity)
    : backend_(backend),
      scene_(scene),
      layout_(layout),
      device_(device),
      ranks_(ranks),
      skin_(shape.skin) {
  const GridParams& gp = shape.params;
  params_.grid = gp;
  params_.n = layout_.total();
  params_.max_candidates = scene_.max_candidates;
  params_.model = scene_.model;
  params_.h = layout_.h;
  params_.mass = layout_.mass;
  params_.gradient_correction = layout_.gradient_correction;
  params_.rest_density = scene_.rest_density;
  params_.sound_speed = scene_.sound_speed;
  params_.clamp_negative_pressure = scene_.clamp_negative_pressure;
  params_.kp = scene_.kp;
  params_.viscosity = scene_.viscosity;
  params_.gravity = scene_.gravity;
  params_.walls = scene_.walls;
  params_.box_min = scene_.box_min;
  params_.box_max = scene_.box_max;
  GridParams local_grid = gp;  // on several ranks the rank layout sets n before any build
  local_grid.n = std::min(gp.n, capacity);
  grid_ = make_hash_grid(backend_, local_grid, capacity);
}

void SphFieldEvaluator::mark(SphStage ended) {
  if (profiling_) marks_.push_back({backend_.timestamp(), ended});
}

// The rebuild on `x` (the counting build; a particle's own cell is among its candidates, so a
// cell fuller than max_candidates is an overflow of the SPH kernels anyway), with x, v and ids
// moved into cell order by its rank pass (x_sorted, v_sorted, ids_sorted).
void SphFieldEvaluator::rebuild_moving(const Buffer<Real4>& x, Buffer<Real4>& x_sorted,
                                       const Buffer<Real4>& v, Buffer<Real4>& v_sorted,
                                       const Buffer<uint32_t>& ids, Buffer<uint32_t>& ids_sorted) {
  build_hash_grid_moving(backend_, grid_, x, scene_.max_candidates,
                         MovedArrays{&x_sorted, &v, &v_sorted, &ids, &ids_sorted});
}

void SphFieldEvaluator::use_rank_layout(const Buffer<Real4>& x) {
  const SphRankLayout& l = ranks_->staged();
  grid_.params.n = l.local;
  params_.grid.n = l.local;
  params_.n = l.local;
  params_.first = l.first;
  params_.count = l.own;
  // The arrays are in cell order already: this build only marks the cells' ranges (its sort
  // keeps the order, being stable).
  build_hash_grid(backend_, grid_, x, {GridBuild::counting, scene_.max_candidates});
}

void SphFieldEvaluator::sort_state() {
  // dfsph's kappa sums (its warm starts, in pos's order) move with the particles.
  const std::array<SphCarried, 2> kappa_sums = {
      SphCarried{device_.kappa_density, device_.kappa_density_t},
      SphCarried{device_.kappa_divergence, device_.kappa_divergence_t}};
  const std::span<const SphCarried> carried(kappa_sums.data(),
                                            scene_.model == SphPressureModel::dfsph ? 2 : 0);
  if (ranks_) {
    ranks_->redistribute(device_.pos, device_.vel, device_.ids, carried, device_.ta, device_.tb,
                         device_.ids_t);
    ranks_->commit();
    use_rank_layout(device_.ta);
  } else {
    rebuild_moving(device_.pos, device_.ta, device_.vel, device_.tb, device_.ids, device_.ids_t);
    for (const SphCarried& c : carried) reorder(backend_, grid_, c.from(), c.to());
  }
  std::swap(device_.pos, device_.ta);
  std::swap(device_.vel, device_.tb);
  std::swap(device_.ids, device_.ids_t);
  if (scene_.model == SphPressureModel::dfsph) {
    std::swap(device_.kappa_density, device_.kappa_density_t);
    std::swap(device_.kappa_divergence, device_.kappa_divergence_t);
  }
  mark(SphStage::grid);
}

void SphFieldEvaluator::rebuild_drifted(std::span<const SphCarried> carried) {
  SphDeviceState& d = device_;
  if (ranks_) {
    ranks_->redistribute(d.xs, d.vs, d.ids, carried, d.ta, d.tb, d.ids_t);
    use_rank_layout(d.ta);
  } else {
    rebuild_moving(d.xs, d.ta, d.vs, d.tb, d.ids, d.ids_t);
    for (const SphCarried& c : carried) reorder(backend_, grid_, c.from(), c.to());
  }
}

Buffer<uint32_t>* SphFieldEvaluator::neighbor_rows() {
  return device_.neighbor_rows.valid() ? &device_.neighbor_rows : nullptr;
}

SphDensityIO SphFieldEvaluator::density_io(const Buffer<Real4>& x, const Buffer<Real4>& v) {
  SphDensityIO io{&x,
                  sph_grid_view(grid_),
                  &device_.density,
                  &device_.pressure,
                  &device_.stats,
                  neighbor_rows()};
  // The neighbour state is kept in one process only (neighbor_state_fits).
  if (device_.neighbor_state.valid()) {
    io.velocities = &v;
    io.neighbor_state = &device_.neighbor_state;
  }
  return io;
}

SphForcesIO SphFieldEvaluator::forces_io(const Buffer<Real4>& x, const Buffer<Real4>& v) {
  SphForcesIO io{&x,
                 &v,
                 &device_.density,
                 &device_.pressure,
                 sph_grid_view(grid_),
                 &device_.accel,
                 &device_.stats,
                 neighbor_rows()};
  if (device_.neighbor_state.valid()) io.neighbor_state = &device_.neighbor_state;
  return io;
}

void SphFieldEvaluator::evaluate(const Buffer<Real4>& x, const Buffer<Real4>& v, SphReach reach) {
  SphStepParams density_params = params_;
  SphDensityIO density = density_io(x, v);
  if (reach != SphReach::none && device_.reach_rows.valid()) {
    density_params.reach = reach;
    density_params.reach_radius = double(params_.grid.cell_size);
    density.reach_rows = &device_.reach_rows;
  }
  sph_density(backend_, density_params, density);
  mark(SphStage::density);
  const SphForcesIO forces = forces_io(x, v);
  if (!ranks_) {
    sph_forces(backend_, params_, forces);
  } else {
    // The halos' density and pressure travel while the forces of the own particles that have
    // no halo neighbour run; then the rest of the own range (its ends).
    ranks_->start_halos(device_.density, device_.pressure);
    const auto [begin, end] = ranks_->interior();
    auto forces_over = [&](uint32_t first, uint32_t last) {
      if (first >= last) return;
      SphStepParams p = params_;
      p.first = first;
      p.count = last - first;
      sph_forces(backend_, p, forces);
    };
    forces_over(begin, end);
    ranks_->finish_halos();
    forces_over(params_.first, begin);
    forces_over(end, params_.first + params_.count);
    ranks_->count_overlapped(end - begin);
  }
  mark(SphStage::forces);
}

void SphFieldEvaluator::integrate(SphStageOp op, double dt, const Buffer<Real4>& x0,
                                  const Buffer<Real4>& v0, const Buffer<Real4>* vk,
                                  Buffer<Real4>* x_out, Buffer<Real4>& v_out, Buffer<Real4>* sum_x,
                                  Buffer<Real4>* sum_v) {
  SphIntegrateParams p;
  p.n = layout_.total();
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
  sph_integrate(
      backend_, p,
      SphIntegrateIO{&x0, &v0, vk, &device_.accel, x_out, &v_out, sum_x, sum_v, &device_.stats});
  mark(SphStage::integrate);
}

SphStepStats SphFieldEvaluator::read_stats(uint32_t w[kSphStatWords]) {
  const std::vector<uint32_t> words = backend_.download(device_.stats);
  std::copy(words.begin(), words.begin() + kSphStatWords, w);
  return stats_from_words(w);
}

SphStepStats SphFieldEvaluator::stats_from_words(uint32_t w[kSphStatWords]) {
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

void SphFieldEvaluator::clear_stats() {
  backend_.fill(device_.stats, 0u);
}

void SphFieldEvaluator::start_stage_times() {
  if (!profiling_) return;
  backend_.finish();
  backend_.reset_timestamps();
  first_mark_ = backend_.timestamp();
}

void SphFieldEvaluator::collect_stage_times() {
  if (!profiling_ || marks_.empty()) return;
  double prev = backend_.timestamp_ns(first_mark_);
  for (const auto& [id, stage] : marks_) {
    const double t = backend_.timestamp_ns(id);
    stage_ms_[size_t(stage)] += (t - prev) * 1e-6;
    prev = t;
  }
  marks_.clear();
}

}  // namespace masav
