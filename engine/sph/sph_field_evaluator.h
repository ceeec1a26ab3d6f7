#pragma once
// The SPH simulation's fields: the hash grid and its rebuilds, density and forces with the
// buffers each evaluation uses (the neighbour row masks, RK4's reach masks and the neighbour
// state where kept), the integrate kernel's calls, the stats words and the stage timing marks.
// The integrators (sph_scheme.h) call these in the order their scheme needs.
//
// Grid rebuilds. Every step starts (Euler, RK4) or ends its drift (leapfrog, dfsph) with a
// rebuild: the counting sort by cell of the current positions, whose rank pass also moves
// positions, velocities and particle ids into cell order (grid_rank_and_move), so the neighbour
// loops read neighbours from contiguous memory. The grid's cells are h wide, h (1 + rk4_skin)
// for RK4 (sph_rk4_scheme.cpp). On several ranks a rebuild is SphRanks::redistribute, which
// leaves the arrays in cell order, and the grid only marks the cells' ranges.
#include <array>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "engine/grid/hash_grid.h"
#include "engine/kernels/backend.h"
#include "engine/sph/sph_params.h"
#include "engine/sph/sph_particles.h"
#include "engine/sph/sph_ranks.h"
#include "engine/sph/sph_state.h"

namespace masav {

class SphDeviceState;

// The grid of a scene: cells of h + skin (skin: RK4's allowed drift of a stage, 0 otherwise)
// over the box. Throws masav::Error where the box needs too many cells.
struct SphGridShape {
  GridParams params;
  double skin = 0;  // m
};
SphGridShape sph_grid_shape(const SphScene& scene, const SphParticles& layout);

class SphFieldEvaluator {
 public:
  // The grid gets room for `capacity` particles (SphDeviceState::capacity()).
  SphFieldEvaluator(Backend& backend, const SphScene& scene, const SphParticles& layout,
                    const SphGridShape& shape, SphDeviceState& device, SphRanks* ranks,
                    uint32_t capacity);

  // The kernels' parameters: on several ranks with the staged layout's counts and own range.
  const SphStepParams& params() const { return params_; }
  double skin() const { return skin_; }
  HashGrid& grid() { return grid_; }

  // The rebuild on `x` (the counting build; a particle's own cell is among its candidates, so a
  // cell fuller than max_candidates is an overflow of the SPH kernels anyway), with x, v and ids
  // moved into cell order by its rank pass (x_sorted, v_sorted, ids_sorted).
  void rebuild_moving(const Buffer<Real4>& x, Buffer<Real4>& x_sorted, const Buffer<Real4>& v,
                      Buffer<Real4>& v_sorted, const Buffer<uint32_t>& ids,
                      Buffer<uint32_t>& ids_sorted);
  // The committed state rebuilt in place: pos, vel, ids (and dfsph's kappa sums) in cell order.
  void sort_state();
  // The rebuild at the end of a drift: xs, vs, ids into the rebuild's arrays ta, tb, ids_t, the
  // `carried` arrays with them (on several ranks through SphRanks::redistribute).
  void rebuild_drifted(std::span<const SphCarried> carried);

  // sph_density's and sph_forces's buffers at x, v in the step's own forms (the row masks and
  // the neighbour state where kept): every evaluation uses them, so a state read between steps
  // runs the pipelines the steps built and compiles none mid-run.
  SphDensityIO density_io(const Buffer<Real4>& x, const Buffer<Real4>& v);
  SphForcesIO forces_io(const Buffer<Real4>& x, const Buffer<Real4>& v);
  Buffer<uint32_t>* neighbor_rows();  // null where the masks are not kept
  // Density and forces at x, v; `reach`: how sph_density uses the reach masks, where kept.
  void evaluate(const Buffer<Real4>& x, const Buffer<Real4>& v, SphReach reach = SphReach::none);
  // One sph_integrate pass (SphStageOp) over the own particles, inside the box's walls.
  void integrate(SphStageOp op, double dt, const Buffer<Real4>& x0, const Buffer<Real4>& v0,
                 const Buffer<Real4>* vk, Buffer<Real4>* x_out, Buffer<Real4>& v_out,
                 Buffer<Real4>* sum_x, Buffer<Real4>* sum_v);

  // The stats words: zeroed before the work they accumulate; read back (one wait); the stats of
  // words just read (reduced over the ranks first, in place).
  void clear_stats();
  SphStepStats read_stats(uint32_t words[kSphStatWords]);
  SphStepStats stats_from_words(uint32_t words[kSphStatWords]);

  // Device time per stage: a timestamp after each stage while profiling is on.
  void set_profiling(bool on) { profiling_ = on; }
  bool profiling() const { return profiling_; }
  void mark(SphStage ended);
  void start_stage_times();    // an attempt's first mark, the device idle before it
  void collect_stage_times();  // the marks' intervals added to stage_ms
  std::array<double, size_t(SphStage::count)>& stage_ms() { return stage_ms_; }
  const std::array<double, size_t(SphStage::count)>& stage_ms() const { return stage_ms_; }

 private:
  // On several ranks: the grid of the staged layout's arrays, already in cell order (x), and the
  // kernels' particle counts and own ranges.
  void use_rank_layout(const Buffer<Real4>& x);

  Backend& backend_;
  const SphScene& scene_;
  const SphParticles& layout_;
  SphDeviceState& device_;
  SphRanks* ranks_;
  SphStepParams params_;
  double skin_ = 0;
  HashGrid grid_;

  bool profiling_ = false;
  std::vector<std::pair<TimestampId, SphStage>> marks_;
  TimestampId first_mark_ = 0;
  std::array<double, size_t(SphStage::count)> stage_ms_{};
};

}  // namespace masav
