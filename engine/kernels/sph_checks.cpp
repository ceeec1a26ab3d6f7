#include <fmt/format.h>

#include <cmath>

#include "engine/core/device_api.h"
#include "engine/core/error.h"
#include "engine/kernels/dfsph_params.h"
#include "engine/kernels/kernel_checks.h"
#include "engine/kernels/sph_kernel_params.h"

namespace masav {
namespace {

void finite_positive(const char* kernel, const char* field, double v, bool allow_zero) {
  if (!std::isfinite(v) || v < 0 || (!allow_zero && v == 0))
    throw_invalid(kernel, field, fmt::format("{}", v),
                  allow_zero ? "finite and >= 0" : "finite and > 0");
}

// A buffer the kernel needs at least `count` elements of (an optional one is null when not
// passed, which is an error where the op reads or writes it).
template <class B>
void need(const DeviceApi& dev, const B* b, size_t count, const char* kernel, const char* field) {
  if (!b)
    throw Error(dev.name(), kernel, fmt::format("no '{}' buffer given", field),
                "pass every buffer the kernel reads or writes");
  if (b->size() < count)
    throw_invalid(kernel, fmt::format("{} size", field), std::to_string(b->size()),
                  fmt::format("at least {} elements", count));
}

void check_view(const DeviceApi& dev, const SphStepParams& p, const Buffer<uint32_t>& cells,
                const Buffer<uint32_t>& cell_start, const Buffer<uint32_t>& cell_end,
                const char* kernel) {
  const size_t n_cells = size_t(grid_cell_count(p.grid));
  need(dev, &cells, p.n, kernel, "cells");
  need(dev, &cell_start, n_cells, kernel, "cell_start");
  need(dev, &cell_end, n_cells, kernel, "cell_end");
}

// The particles computed, [first, first + count), lie within the n.
template <class P>
void check_particle_range(const P& p, const char* kernel) {
  if (p.first > p.n)
    throw_invalid(kernel, "first", std::to_string(p.first),
                  fmt::format("at most the particle count n = {}", p.n));
  if (p.count != kSphAllParticles && uint64_t(p.first) + p.count > p.n)
    throw_invalid(kernel, "count", std::to_string(p.count),
                  fmt::format("at most n - first = {} (or kSphAllParticles: from first to n)",
                              p.n - p.first));
}

void check_sph_step(const DeviceApi& dev, const SphStepParams& p, const char* kernel) {
  check_grid(p.grid, kernel);
  if (p.n != p.grid.n)
    throw_invalid(kernel, "n", std::to_string(p.n),
                  fmt::format("equal to the grid's point count {}", p.grid.n));
  check_particle_range(p, kernel);
  finite_positive(kernel, "h", p.h, false);
  if (double(p.grid.cell_size) < p.h)
    throw_invalid(kernel, "grid cell_size", fmt::format("{}", p.grid.cell_size),
                  fmt::format(">= h = {} so that the 27 cells around a particle hold every "
                              "neighbour",
                              p.h));
  finite_positive(kernel, "mass", p.mass, false);
  finite_positive(kernel, "rest_density", p.rest_density, false);
  finite_positive(kernel, "gradient_correction", p.gradient_correction, false);
  finite_positive(kernel, "viscosity", p.viscosity, true);
  if (p.model == SphPressureModel::wcsph)
    finite_positive(kernel, "sound_speed", p.sound_speed, false);
  else if (p.model == SphPressureModel::thesis)
    finite_positive(kernel, "kp", p.kp, true);
  for (double g : {p.gravity.x, p.gravity.y, p.gravity.z})
    if (!std::isfinite(g))
      throw_invalid(kernel, "gravity",
                    fmt::format("({}, {}, {})", p.gravity.x, p.gravity.y, p.gravity.z), "finite");
  if (p.walls) {
    const double lo[3] = {p.box_min.x, p.box_min.y, p.box_min.z};
    const double hi[3] = {p.box_max.x, p.box_max.y, p.box_max.z};
    for (int a = 0; a < 3; ++a)
      if (!std::isfinite(lo[a]) || !std::isfinite(hi[a]) || !(lo[a] < hi[a]))
        throw_invalid(kernel, "box", fmt::format("[{}, {}] on axis {}", lo[a], hi[a], a),
                      "finite with min < max on every axis");
  }
  check_candidates(dev, p.max_candidates, kernel, "max_candidates", kSphWalks);
}

// The optional neighbour row masks: kSphRowMaskWords words per particle when given.
void check_neighbor_rows(const Buffer<uint32_t>* rows, const SphStepParams& p, const char* kernel) {
  const size_t need_words = size_t(kSphRowMaskWords) * p.n;
  if (rows && rows->size() < need_words)
    throw_invalid(kernel, "neighbor_rows size", std::to_string(rows->size()),
                  fmt::format("at least {} elements ({} words per particle, {} particles), or no "
                              "neighbor_rows buffer",
                              need_words, kSphRowMaskWords, p.n));
}

// The optional neighbour state: kSphStateStride elements per particle when given.
void check_neighbor_state(const Buffer<Real4>* state, const SphStepParams& p, const char* kernel) {
  const size_t need_elems = size_t(kSphStateStride) * p.n;
  if (state->size() < need_elems)
    throw_invalid(kernel, "neighbor_state size", std::to_string(state->size()),
                  fmt::format("at least {} elements ({} per particle, {} particles), or no "
                              "neighbor_state buffer",
                              need_elems, kSphStateStride, p.n));
}

// sph_density's reach masks (SphReach): the mode, the radius the record walk can reach within the
// 27 cells, and a buffer of their own.
void check_reach(const Buffer<uint32_t>* reach_rows, const Buffer<uint32_t>* neighbor_rows,
                 const SphStepParams& p, const char* kernel) {
  const uint32_t mode = uint32_t(p.reach);
  if (mode > uint32_t(SphReach::walk))
    throw_invalid(kernel, "reach", std::to_string(mode), "none (0), record (1) or walk (2)");
  if (p.reach == SphReach::none) return;
  if (!reach_rows)
    throw_invalid(
        kernel, "reach_rows", "none",
        fmt::format("{} words per particle when reach is record or walk", kSphRowMaskWords));
  if (reach_rows == neighbor_rows)
    throw_invalid(kernel, "reach_rows", "the neighbor_rows buffer", "a buffer of its own");
  const size_t need_words = size_t(kSphRowMaskWords) * p.n;
  if (reach_rows->size() < need_words)
    throw_invalid(kernel, "reach_rows size", std::to_string(reach_rows->size()),
                  fmt::format("at least {} elements ({} words per particle, {} particles)",
                              need_words, kSphRowMaskWords, p.n));
  if (p.reach == SphReach::record && !(std::isfinite(p.reach_radius) && p.reach_radius >= p.h &&
                                       p.reach_radius <= double(p.grid.cell_size)))
    throw_invalid(kernel, "reach_radius", fmt::format("{}", p.reach_radius),
                  fmt::format("in [h, grid cell_size] = [{}, {}]: the 27 cells around a "
                              "particle hold every candidate within it",
                              p.h, double(p.grid.cell_size)));
}

// The DFSPH kernels' common parameters: a dfsph step and a solve.
void check_dfsph(const DeviceApi& dev, const DfsphParams& p, const Buffer<Real4>& positions,
                 const Buffer<uint32_t>& cells, const Buffer<uint32_t>& cell_start,
                 const Buffer<uint32_t>& cell_end, const Buffer<uint32_t>* neighbor_rows,
                 const char* kernel) {
  check_sph_step(dev, p.step, kernel);  // with the range computed, [first, first + count)
  if (p.step.model != SphPressureModel::dfsph)
    throw_invalid(kernel, "model", std::to_string(uint32_t(p.step.model)), "dfsph (2)");
  const uint32_t solve = uint32_t(p.solve);
  if (solve > uint32_t(DfsphSolve::density))
    throw_invalid(kernel, "solve", std::to_string(solve), "divergence (0) or density (1)");
  if (!std::isfinite(p.dt) || !(p.dt > 0))
    throw_invalid(kernel, "dt", fmt::format("{}", p.dt), "finite and > 0 (seconds)");
  if (p.slot >= kDfsphMaxSlots)
    throw_invalid(kernel, "slot", std::to_string(p.slot),
                  fmt::format("below {} (one residual slot per iteration)", kDfsphMaxSlots));
  if (!(p.warm_scale >= 0 && p.warm_scale <= 1))
    throw_invalid(kernel, "warm_scale", fmt::format("{}", p.warm_scale), "in [0, 1]");
  need(dev, &positions, p.step.n, kernel, "positions");
  check_view(dev, p.step, cells, cell_start, cell_end, kernel);
  check_neighbor_rows(neighbor_rows, p.step, kernel);
}

// A call that stops on a residual slot (DfsphParams::stop_slot) reads it from `residual`; one
// that adds to slot p.slot (dfsph_rate: `adds`) must stop on another.
void check_stop(const DfsphParams& p, const Buffer<uint32_t>* residual, bool adds,
                const char* kernel) {
  if (p.stop_slot == kDfsphNoStop) return;
  if (p.stop_slot >= kDfsphMaxSlots)
    throw_invalid(kernel, "stop_slot", std::to_string(p.stop_slot),
                  fmt::format("below {}, or kDfsphNoStop", kDfsphMaxSlots));
  if (!residual)
    throw_invalid(kernel, "residual", "none", "the residual words when stop_slot is set");
  if (adds && p.stop_slot == p.slot)
    throw_invalid(kernel, "stop_slot", std::to_string(p.stop_slot),
                  fmt::format("another than slot {} (the one this call adds to)", p.slot));
}

}  // namespace

void validate(const DeviceApi& dev, const DfsphParams& p, const Buffer<Real4>& positions,
              const Buffer<uint32_t>& cells, const Buffer<uint32_t>& cell_start,
              const Buffer<uint32_t>& cell_end, const Buffer<Real>& factor,
              const Buffer<uint32_t>& stats, const Buffer<uint32_t>* neighbor_rows) {
  const char* k = "dfsph_factor";
  check_dfsph(dev, p, positions, cells, cell_start, cell_end, neighbor_rows, k);
  if (p.stop_slot != kDfsphNoStop)
    throw_invalid(k, "stop_slot", std::to_string(p.stop_slot), "kDfsphNoStop (it never stops)");
  need(dev, &factor, p.step.n, k, "factor");
  need(dev, &stats, kSphStatWords, k, "stats");
}

void validate(const DeviceApi& dev, const DfsphParams& p, const Buffer<Real4>& positions,
              const Buffer<Real4>& velocities, const Buffer<Real>& density,
              const Buffer<Real>& factor, const Buffer<uint32_t>& cells,
              const Buffer<uint32_t>& cell_start, const Buffer<uint32_t>& cell_end,
              const Buffer<Real>& kappa, const Buffer<Real>& kappa_sum,
              const Buffer<uint32_t>& residual, const Buffer<uint32_t>* neighbor_rows) {
  const char* k = "dfsph_rate";
  check_dfsph(dev, p, positions, cells, cell_start, cell_end, neighbor_rows, k);
  need(dev, &velocities, p.step.n, k, "velocities");
  need(dev, &density, p.step.n, k, "density");
  need(dev, &factor, p.step.n, k, "factor");
  need(dev, &kappa, p.step.n, k, "kappa");
  need(dev, &kappa_sum, p.step.n, k, "kappa_sum");
  need(dev, &residual, kDfsphResidualWords, k, "residual");
  check_stop(p, &residual, true, k);
}

void validate(const DeviceApi& dev, const DfsphParams& p, const Buffer<Real4>& positions,
              const Buffer<Real>& kappa, const Buffer<uint32_t>& cells,
              const Buffer<uint32_t>& cell_start, const Buffer<uint32_t>& cell_end,
              const Buffer<Real4>& velocities, const Buffer<uint32_t>& stats,
              const Buffer<uint32_t>* residual, const Buffer<uint32_t>* neighbor_rows) {
  const char* k = "dfsph_correct";
  check_dfsph(dev, p, positions, cells, cell_start, cell_end, neighbor_rows, k);
  need(dev, &kappa, p.step.n, k, "kappa");
  need(dev, &velocities, p.step.n, k, "velocities");
  need(dev, &stats, kSphStatWords, k, "stats");
  if (residual) need(dev, residual, kDfsphResidualWords, k, "residual");
  check_stop(p, residual, false, k);
}

void validate(const DeviceApi& dev, const SphStepParams& p, const Buffer<Real4>& positions,
              const Buffer<uint32_t>& cells, const Buffer<uint32_t>& cell_start,
              const Buffer<uint32_t>& cell_end, const Buffer<Real>& density,
              const Buffer<Real>& pressure, const Buffer<uint32_t>& stats,
              const Buffer<Real4>* velocities, const Buffer<Real4>* neighbor_state,
              const Buffer<uint32_t>* reach_rows, const Buffer<uint32_t>* neighbor_rows) {
  const char* k = "sph_density";
  check_sph_step(dev, p, k);
  need(dev, &positions, p.n, k, "positions");
  check_view(dev, p, cells, cell_start, cell_end, k);
  need(dev, &density, p.n, k, "density");
  need(dev, &pressure, p.n, k, "pressure");
  need(dev, &stats, kSphStatWords, k, "stats");
  check_neighbor_rows(neighbor_rows, p, k);
  check_reach(reach_rows, neighbor_rows, p, k);
  if (neighbor_state) {
    check_neighbor_state(neighbor_state, p, k);
    need(dev, velocities, p.n, k, "velocities");
    if (neighbor_state == &positions || neighbor_state == velocities)
      throw_invalid(k, "neighbor_state", "the positions or velocities buffer",
                    "a buffer of its own (it is written while they are read)");
  }
}

void validate(const DeviceApi& dev, const SphStepParams& p, const Buffer<Real4>& positions,
              const Buffer<Real4>& velocities, const Buffer<Real>& density,
              const Buffer<Real>& pressure, const Buffer<uint32_t>& cells,
              const Buffer<uint32_t>& cell_start, const Buffer<uint32_t>& cell_end,
              const Buffer<Real4>& accel, const Buffer<uint32_t>& stats,
              const Buffer<Real4>* neighbor_state, const Buffer<uint32_t>* neighbor_rows) {
  const char* k = "sph_forces";
  check_sph_step(dev, p, k);
  need(dev, &positions, p.n, k, "positions");
  need(dev, &velocities, p.n, k, "velocities");
  need(dev, &density, p.n, k, "density");
  need(dev, &pressure, p.n, k, "pressure");
  check_view(dev, p, cells, cell_start, cell_end, k);
  need(dev, &accel, p.n, k, "accel");
  need(dev, &stats, kSphStatWords, k, "stats");
  check_neighbor_rows(neighbor_rows, p, k);
  if (neighbor_state) {
    check_neighbor_state(neighbor_state, p, k);
    if (neighbor_state == &accel)
      throw_invalid(k, "neighbor_state", "the accel buffer", "a buffer of its own");
  }
}

void validate(const DeviceApi& dev, const SphIntegrateParams& p, const Buffer<Real4>* x0,
              const Buffer<Real4>& v0, const Buffer<Real4>* vk, const Buffer<Real4>& accel,
              const Buffer<Real4>* x_out, const Buffer<Real4>& v_out, const Buffer<Real4>* sum_x,
              const Buffer<Real4>* sum_v, const Buffer<uint32_t>& stats) {
  const char* k = "sph_integrate";
  const uint32_t op = uint32_t(p.op);
  if (op > uint32_t(SphStageOp::drift)) throw_invalid(k, "op", std::to_string(op), "a SphStageOp");
  if (!std::isfinite(p.dt) || !(p.dt > 0))
    throw_invalid(k, "dt", fmt::format("{}", p.dt), "finite and > 0 (seconds)");
  if (p.walls) {
    const double lo[3] = {p.box_min.x, p.box_min.y, p.box_min.z};
    const double hi[3] = {p.box_max.x, p.box_max.y, p.box_max.z};
    for (int a = 0; a < 3; ++a)
      if (!std::isfinite(lo[a]) || !std::isfinite(hi[a]) || !(lo[a] < hi[a]))
        throw_invalid(k, "box", fmt::format("[{}, {}] on axis {}", lo[a], hi[a], a),
                      "finite with min < max on every axis");
  }
  if (!(p.restitution >= 0 && p.restitution <= 1))
    throw_invalid(k, "restitution", fmt::format("{}", p.restitution), "in [0, 1]");
  if (!(p.tangential_damping >= 0 && p.tangential_damping <= 1))
    throw_invalid(k, "tangential_damping", fmt::format("{}", p.tangential_damping), "in [0, 1]");
  check_particle_range(p, k);
  const SphStageOp o = p.op;
  const bool rk4 = o >= SphStageOp::rk4_stage1 && o <= SphStageOp::rk4_final;
  need(dev, &v0, p.n, k, "v0");
  need(dev, &accel, p.n, k, "accel");
  need(dev, &v_out, p.n, k, "v_out");
  need(dev, &stats, kSphStatWords, k, "stats");
  if (o != SphStageOp::kick && o != SphStageOp::accelerate) {
    need(dev, x0, p.n, k, "x0");
    need(dev, x_out, p.n, k, "x_out");
  }
  if (rk4 && o != SphStageOp::rk4_stage1) need(dev, vk, p.n, k, "vk");
  if (rk4) {
    need(dev, sum_x, p.n, k, "sum_x");
    need(dev, sum_v, p.n, k, "sum_v");
  }
  if (o == SphStageOp::kick_drift) need(dev, sum_v, p.n, k, "sum_v");
}

}  // namespace masav
