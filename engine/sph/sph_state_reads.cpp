// SphStateReader: the state in particle-id order, with density and pressure at its positions
// (evaluated on a re-sorted scratch copy when the last fields belong to an older state); on
// several ranks the own particles and their gather (see the header).
#include "engine/sph/sph_state_reads.h"

#include <optional>
#include <utility>

#include "engine/sph/sph_device_state.h"
#include "engine/sph/sph_field_evaluator.h"
#include "engine/sph/sph_kernel_calls.h"
#include "engine/sph/sph_rank_gather.h"

namespace masav {

SphState sized_state(size_t n) {
  SphState s;
  s.positions.resize(n);
  s.velocities.resize(n);
  s.density.resize(n);
  s.pressure.resize(n);
  s.neighbors.resize(n);
  return s;
}

SphStatsKeeper::SphStatsKeeper(Backend& backend, Buffer<uint32_t>& stats, bool block_open)
    : backend_(backend), stats_(stats) {
  // Read behind the work so far, taken at the end of the scope (no wait of its own).
  if (block_open) ticket_ = backend_.read_async(stats_);
  backend_.fill(stats_, 0u);
}

SphStatsKeeper::~SphStatsKeeper() {
  if (!ticket_) return;
  try {
    const std::vector<uint32_t> block = backend_.take_u32s(ticket_);
    backend_.upload(stats_, block);
  } catch (...) {  // a device error: the caller's next call reports it
  }
}

SphState SphStateReader::download() {
  if (c_.ranks) return download_ranks();
  std::optional<SphStatsKeeper> keep;  // to the end: its read is taken after the state's
  SphStateReads reads = queue(keep);
  return take(reads);
}

SphStateReads SphStateReader::queue(std::optional<SphStatsKeeper>& keep) {
  SphDeviceState& d = c_.device;
  SphFieldEvaluator& f = c_.fields;
  const Buffer<Real4>* px = &d.pos;
  const Buffer<Real4>* pv = &d.vel;
  const Buffer<uint32_t>* pid = &d.ids;
  if (!c_.progress.fields_current) {
    // Density at the current positions without touching the committed state: sort copies of
    // the positions, velocities and ids into a fresh grid (scratch buffers), evaluate there.
    f.rebuild_moving(d.pos, d.ta, d.vel, d.tb, d.ids, d.ids_t);
    keep.emplace(c_.backend, d.stats, c_.progress.block_open);
    // The steps' own kernel forms: the watchdog's read every SphWatchdog::kEnergyEvery steps
    // compiles no pipeline mid-run (the neighbour state it writes is the next step's to replace).
    sph_density(c_.backend, f.params(), f.density_io(d.ta, d.tb));
    sph_forces(c_.backend, f.params(), f.forces_io(d.ta, d.tb));
    c_.progress.accel_valid = false;
    px = &d.ta;
    pv = &d.tb;
    pid = &d.ids_t;
    // dfsph's pressure, its density solve's kappa sum times rho^2, in the scratch order.
    if (c_.dfsph()) reorder(c_.backend, f.grid(), d.kappa_density.impl(), d.kappa.impl());
  }
  // Every array's copy queued behind the evaluation, taken together: one wait for all of them.
  SphStateReads r;
  r.pos = c_.backend.read_async(*px);
  r.vel = c_.backend.read_async(*pv);
  r.ids = c_.backend.read_async(*pid);
  r.rho = c_.backend.read_async(d.density);
  r.pr = c_.backend.read_async(c_.dfsph() ? (c_.progress.fields_current ? d.kappa_density : d.kappa)
                                          : d.pressure);
  r.acc = c_.backend.read_async(d.accel);
  return r;
}

SphState SphStateReader::take(SphStateReads& r) {
  try {
    return take_reads(r);
  } catch (...) {
    drop(r);  // the reads not taken yet: their slots stay free for the next run
    throw;
  }
}

SphState SphStateReader::take_reads(SphStateReads& r) {
  const auto pos = c_.backend.take_real4s(std::exchange(r.pos, 0));
  const auto vel = c_.backend.take_real4s(std::exchange(r.vel, 0));
  const auto ids = c_.backend.take_u32s(std::exchange(r.ids, 0));
  const auto rho = c_.backend.take_reals(std::exchange(r.rho, 0));
  std::vector<double> pr = c_.backend.take_reals(std::exchange(r.pr, 0));
  const auto acc = c_.backend.take_real4s(std::exchange(r.acc, 0));
  if (c_.dfsph()) dfsph_pressure(pr, rho);
  SphState s = sized_state(c_.n());
  for (uint32_t i = 0; i < c_.n(); ++i) {
    const uint32_t id = ids[i];
    s.positions[id] = pos[i];
    s.velocities[id] = vel[i];
    s.density[id] = rho[i];
    s.pressure[id] = pr[i];
    s.neighbors[id] = acc[i].w + 1.0;
  }
  return s;
}

void SphStateReader::dfsph_pressure(std::vector<double>& kappa,
                                    const std::vector<double>& rho) const {
  // p / rho^2 of the density solve, times rho^2 and the lattice's gradient moment: the SPH
  // gradient of a pressure field on the rest lattice is 1 / gradient_correction of its true
  // gradient (0.78 for the spiky density's lattice mass at h = 2 dx), so the pressure that
  // balances a force is that much larger than the physical one.
  for (size_t i = 0; i < kappa.size(); ++i)
    kappa[i] *= rho[i] * rho[i] / c_.layout.gradient_correction;
}

void SphStateReader::drop(SphStateReads& r) {
  for (uint64_t* t : {&r.pos, &r.vel, &r.ids, &r.rho, &r.pr, &r.acc})
    c_.backend.discard_read(std::exchange(*t, 0));
}

void SphStateReader::refresh_fields_ranks() {
  if (c_.progress.fields_current) return;
  // Density at the current positions: the committed state itself is re-sorted (a rebuild on
  // unchanged positions is what the next step's rebuild gives anyway) and evaluated there.
  SphDeviceState& d = c_.device;
  c_.fields.sort_state();
  const SphStatsKeeper keep(c_.backend, d.stats, c_.progress.block_open);
  c_.fields.evaluate(d.pos, d.vel);
  c_.progress.accel_valid = false;
  c_.progress.fields_current = true;
}

SphState SphStateReader::download_own(std::vector<uint32_t>& ids) {
  if (!c_.ranks) {
    SphState s = download();
    ids.resize(c_.n());
    for (uint32_t i = 0; i < c_.n(); ++i) ids[i] = i;
    return s;
  }
  refresh_fields_ranks();
  Backend& b = c_.backend;
  const SphDeviceState& d = c_.device;
  const SphRanks& r = *c_.ranks;
  SphState s;
  ids = own_values(b, r, d.ids);
  s.positions = own_values(b, r, d.pos);
  s.velocities = own_values(b, r, d.vel);
  s.density = own_values(b, r, d.density);
  s.pressure = own_values(b, r, c_.dfsph() ? d.kappa_density : d.pressure);
  if (c_.dfsph()) dfsph_pressure(s.pressure, s.density);
  for (const Vec4d& a : own_values(b, r, d.accel)) s.neighbors.push_back(a.w + 1.0);
  return s;
}

SphState SphStateReader::download_ranks() {
  std::vector<uint32_t> ids;
  const SphState own = download_own(ids);
  return gather_state(c_.backend, *c_.ranks, own, ids, c_.n());
}

}  // namespace masav
