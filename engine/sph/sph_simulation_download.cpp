// SphSimulation::download: the state in particle-id order, with density and pressure at its
// positions (evaluated on a re-sorted scratch copy when the last fields belong to an older
// state).
#include <optional>
#include <utility>

#include "engine/sph/sph_kernel_calls.h"
#include "engine/sph/sph_simulation.h"

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

SphSimulation::StatsKeeper::StatsKeeper(SphSimulation& sim) : sim_(sim) {
  // Read behind the work so far, taken at the end of the scope (no wait of its own).
  if (sim_.block_open_) ticket_ = sim_.backend_.read_async(sim_.stats_buf_);
  sim_.backend_.fill(sim_.stats_buf_, 0u);
}

SphSimulation::StatsKeeper::~StatsKeeper() {
  if (!ticket_) return;
  try {
    const std::vector<uint32_t> block = sim_.backend_.take_u32s(ticket_);
    sim_.backend_.upload(sim_.stats_buf_, block);
  } catch (...) {  // a device error: the caller's next call reports it
  }
}

SphState SphSimulation::download() {
  if (ranks_) return download_ranks();
  std::optional<StatsKeeper> keep;  // to the end: its read is taken after the state's
  StateReads reads = queue_state_reads(keep);
  return take_state(reads);
}

SphSimulation::StateReads SphSimulation::queue_state_reads(std::optional<StatsKeeper>& keep) {
  const Buffer<Real4>* px = &pos_;
  const Buffer<Real4>* pv = &vel_;
  const Buffer<uint32_t>* pid = &ids_;
  if (!fields_current_) {
    // Density at the current positions without touching the committed state: sort copies of
    // the positions, velocities and ids into a fresh grid (scratch buffers), evaluate there.
    rebuild_moving(pos_, ta_, vel_, tb_, ids_, ids_t_);
    keep.emplace(*this);
    // The steps' own kernel forms: the watchdog's read every SphWatchdog::kEnergyEvery steps
    // compiles no pipeline mid-run (the neighbour state it writes is the next step's to replace).
    sph_density(backend_, step_params_, density_io(ta_, tb_));
    sph_forces(backend_, step_params_, forces_io(ta_, tb_));
    accel_valid_ = false;
    px = &ta_;
    pv = &tb_;
    pid = &ids_t_;
    // dfsph's pressure, its density solve's kappa sum times rho^2, in the scratch order.
    if (dfsph()) reorder(backend_, grid_, kappa_density_.impl(), kappa_.impl());
  }
  // Every array's copy queued behind the evaluation, taken together: one wait for all of them.
  StateReads r;
  r.pos = backend_.read_async(*px);
  r.vel = backend_.read_async(*pv);
  r.ids = backend_.read_async(*pid);
  r.rho = backend_.read_async(density_);
  r.pr = backend_.read_async(dfsph() ? (fields_current_ ? kappa_density_ : kappa_) : pressure_);
  r.acc = backend_.read_async(accel_);
  return r;
}

SphState SphSimulation::take_state(StateReads& r) {
  try {
    return take_state_reads(r);
  } catch (...) {
    drop_state(r);  // the reads not taken yet: their slots stay free for the next run
    throw;
  }
}

SphState SphSimulation::take_state_reads(StateReads& r) {
  const auto pos = backend_.take_real4s(std::exchange(r.pos, 0));
  const auto vel = backend_.take_real4s(std::exchange(r.vel, 0));
  const auto ids = backend_.take_u32s(std::exchange(r.ids, 0));
  const auto rho = backend_.take_reals(std::exchange(r.rho, 0));
  std::vector<double> pr = backend_.take_reals(std::exchange(r.pr, 0));
  const auto acc = backend_.take_real4s(std::exchange(r.acc, 0));
  if (dfsph()) dfsph_pressure(pr, rho);
  SphState s = sized_state(n_);
  for (uint32_t i = 0; i < n_; ++i) {
    const uint32_t id = ids[i];
    s.positions[id] = pos[i];
    s.velocities[id] = vel[i];
    s.density[id] = rho[i];
    s.pressure[id] = pr[i];
    s.neighbors[id] = acc[i].w + 1.0;
  }
  return s;
}

void SphSimulation::dfsph_pressure(std::vector<double>& kappa,
                                   const std::vector<double>& rho) const {
  // p / rho^2 of the density solve, times rho^2 and the lattice's gradient moment: the SPH
  // gradient of a pressure field on the rest lattice is 1 / gradient_correction of its true
  // gradient (0.78 for the spiky density's lattice mass at h = 2 dx), so the pressure that
  // balances a force is that much larger than the physical one.
  for (size_t i = 0; i < kappa.size(); ++i)
    kappa[i] *= rho[i] * rho[i] / layout_.gradient_correction;
}

void SphSimulation::drop_state(StateReads& r) {
  for (uint64_t* t : {&r.pos, &r.vel, &r.ids, &r.rho, &r.pr, &r.acc})
    backend_.discard_read(std::exchange(*t, 0));
}

}  // namespace masav
