// SphDeviceState: what a particle costs on the device, what fits (the masks, the neighbour state,
// run()'s checkpoints), the buffers' allocation and, on several ranks, their growth.
#include "engine/sph/sph_device_state.h"

#include <fmt/format.h>

#include <algorithm>

#include "engine/core/error.h"
#include "engine/kernels/kernel_checks.h"

namespace masav {
namespace {

// Device memory the simulation needs per particle: 10 Real4 arrays, 2 Real (8 with dfsph's
// factor and kappas), 2 ids, the grid's 4 words (cells, order, and the counting build's counts
// and ranks), `mask_sets` sets of row masks (the neighbour rows and RK4's reach masks, where
// kept), with `state` the neighbour state (kSphStateStride Real4), and with `checkpoint` one of
// run()'s checkpoints (3 Real4 and ids).
uint64_t bytes_per_particle(const Backend& b, int mask_sets, bool checkpoint = false,
                            bool dfsph = false, bool state = false) {
  return 10 * 4 * b.real_bytes() + (dfsph ? 8 : 2) * b.real_bytes() + 6 * 4 +
         uint64_t(mask_sets) * kSphRowMaskWords * 4 +
         (state ? kSphStateStride * 4 * b.real_bytes() : 0) +
         (checkpoint ? 3 * 4 * b.real_bytes() + 4 : 0);
}

// How many of the checkpoints run() keeps for its blocks (up to `wanted`) fit the memory budget
// check_capacity applies (with the masks and the neighbour state that are kept).
int keeps_checkpoints(const Backend& b, uint64_t n, int mask_sets, bool state, int wanted) {
  const Capabilities& caps = b.caps();
  const uint64_t base = bytes_per_particle(b, mask_sets, false, false, state);
  const uint64_t each = bytes_per_particle(b, mask_sets, true, false, state) - base;
  int k = 0;
  while (k < wanted && (!caps.device_memory_bytes ||
                        n * (base + uint64_t(k + 1) * each) <= caps.device_memory_bytes / 2))
    ++k;
  return k;
}

// Whether sph_density records neighbour row masks for sph_forces, which then visits only the
// neighbours instead of testing every candidate of the 27 cells again: on the fp32 backends
// (Vulkan, CUDA), not on the CPU reference, which keeps its own neighbour lists
// (engine/cpu/cpu_sph_lists.h) and would only fill the masks for nothing. Only where they fit
// one buffer and the memory budget check_capacity applies; elsewhere the kernels walk every
// candidate, as without masks.
bool keeps_neighbor_rows(const Backend& b, uint64_t n, bool dfsph) {
  const Capabilities& caps = b.caps();
  if (caps.real_is_double) return false;
  const uint64_t mask_bytes = n * kSphRowMaskWords * 4;
  if (caps.max_buffer_bytes && mask_bytes > caps.max_buffer_bytes) return false;
  return !caps.device_memory_bytes ||
         n * bytes_per_particle(b, 1, false, dfsph) <= caps.device_memory_bytes / 2;
}

// Whether RK4's first evaluation records the reach masks that its other three walk (SphReach):
// on every backend (the CPU reference's lists use them too), where they fit one buffer and, with
// the neighbour rows when kept, the memory budget check_capacity applies; elsewhere every
// evaluation walks the inflated cells. The masks cost what they save on a CPU device (the CPU
// reference's RK4 step at 32,768 particles 71.7-73.2 against 70.8-84.1 ms without) and save a
// tenth of lavapipe's density pass (59.7-64.2 against 64.3-66.9 ms), docs/performance.md.
bool keeps_reach_rows(const Backend& b, uint64_t n, bool neighbor_rows) {
  const Capabilities& caps = b.caps();
  const uint64_t mask_bytes = n * kSphRowMaskWords * 4;
  if (caps.max_buffer_bytes && mask_bytes > caps.max_buffer_bytes) return false;
  return !caps.device_memory_bytes ||
         n * bytes_per_particle(b, neighbor_rows ? 2 : 1) <= caps.device_memory_bytes / 2;
}

// Whether sph_density writes the neighbour state that sph_forces then reads (kSphStateStride):
// where SphTuning::neighbor_state allows (auto: on), in one process (a rank's halos exchange
// density and pressure, not the state), where it fits one buffer and, with the masks kept, the
// memory budget check_capacity applies. dfsph never: its viscosity forces use the velocities its
// divergence solve changed after sph_density.
bool neighbor_state_fits(const Backend& b, uint64_t n, bool wanted, int mask_sets) {
  if (!wanted) return false;
  const Capabilities& caps = b.caps();
  const uint64_t state_bytes = n * kSphStateStride * 4 * b.real_bytes();
  if (caps.max_buffer_bytes && state_bytes > caps.max_buffer_bytes) return false;
  return !caps.device_memory_bytes ||
         n * bytes_per_particle(b, mask_sets, false, false, true) <= caps.device_memory_bytes / 2;
}

}  // namespace

// The particles a rank's buffers start with room for: all of them in one process; on several
// ranks an equal share and a quarter more (plus 1,024) for its halos (reserve() grows them).
uint32_t SphDeviceState::initial_capacity(uint64_t particles, int ranks) {
  if (ranks <= 1) return uint32_t(particles);
  const uint64_t share = (particles + uint64_t(ranks) - 1) / uint64_t(ranks);
  return uint32_t(std::min<uint64_t>(particles, share + share / 4 + 1024));
}

namespace {

// On several ranks the limits are a rank's (its share with room for halos, `n`), said so.
std::string per_rank_note(uint64_t n, int ranks) {
  if (ranks <= 1) return "";
  return fmt::format(
      " per rank's buffers (now {}: 1/{} of the particles and room for halos); "
      "use more ranks,",
      n, ranks);
}

}  // namespace

void SphDeviceState::check_buffer_size(const Backend& b, uint64_t particles, int ranks) {
  const Capabilities& caps = b.caps();
  const uint64_t n = initial_capacity(particles, ranks);
  const uint64_t real4 = 4 * b.real_bytes();
  if (caps.max_buffer_bytes && n * real4 > caps.max_buffer_bytes)
    throw_invalid("sph scene", "particles", std::to_string(particles),
                  fmt::format("at most {}{} on {} (one buffer of positions holds at most {} MiB); "
                              "use fewer particles or a device with larger buffers",
                              caps.max_buffer_bytes / real4, per_rank_note(n, ranks),
                              caps.device_name, caps.max_buffer_bytes >> 20));
}

void SphDeviceState::check_capacity(const Backend& b, const SphScene& s, int ranks) {
  // The obstacle is checked once its size is known (check_buffer_size again).
  check_buffer_size(b, s.particles, ranks);
  const Capabilities& caps = b.caps();
  const uint64_t n = initial_capacity(s.particles, ranks);
  // Without the row masks: a count they do not fit runs without them.
  const uint64_t per_particle = bytes_per_particle(b, 0, false, s.model == SphPressureModel::dfsph);
  if (caps.device_memory_bytes && n * per_particle > caps.device_memory_bytes / 2)
    throw_invalid("sph scene", "particles", std::to_string(s.particles),
                  fmt::format("at most {}{} on {} ({} bytes per particle, {} MiB of memory)",
                              caps.device_memory_bytes / 2 / per_particle, per_rank_note(n, ranks),
                              caps.device_name, per_particle, caps.device_memory_bytes >> 20));
}

SphDeviceState::SphDeviceState(Backend& backend, const SphScene& scene, uint32_t particles,
                               int ranks)
    : backend_(backend),
      scene_(scene),
      n_(particles),
      ranks_(ranks > 1),
      capacity_(initial_capacity(particles, ranks)) {}

void SphDeviceState::allocate() {
  stats = backend_.create<uint32_t>(kSphStatWords, "sph stats");
  const bool dfsph = scene_.model == SphPressureModel::dfsph;
  const size_t c = capacity_;
  auto real4 = [&](const char* label) { return backend_.create<Real4>(c, label); };
  pos = real4("sph positions");
  vel = real4("sph velocities");
  xs = real4("sph stage positions");
  vs = real4("sph stage velocities");
  sum_x = real4("sph rk4 position sums");
  sum_v = real4("sph rk4 velocity sums");
  ta = real4("sph sorted positions");
  tb = real4("sph sorted velocities");
  tc = real4("sph sorted predicted velocities");
  accel = real4("sph accelerations");
  density = backend_.create<Real>(c, "sph density");
  pressure = backend_.create<Real>(c, "sph pressure");
  ids = backend_.create<uint32_t>(c, "sph ids");
  ids_t = backend_.create<uint32_t>(c, "sph sorted ids");
  // Whether the row masks and the block checkpoint fit is decided once, for the buffers' first
  // size; a rank's growth keeps what it has.
  if (keeps_neighbor_rows(backend_, c, dfsph))
    neighbor_rows =
        backend_.create<uint32_t>(size_t(kSphRowMaskWords) * c, "sph neighbour row masks");
  if (scene_.integrator == SphIntegrator::rk4 && !dfsph &&
      keeps_reach_rows(backend_, c, neighbor_rows.valid()))
    reach_rows = backend_.create<uint32_t>(size_t(kSphRowMaskWords) * c, "sph rk4 reach masks");
  const int mask_sets = int(neighbor_rows.valid()) + int(reach_rows.valid());
  if (!dfsph && !ranks_ &&
      neighbor_state_fits(backend_, c, resolve(backend_.tuning().sph.neighbor_state, true),
                          mask_sets))
    neighbor_state = backend_.create<Real4>(size_t(kSphStateStride) * c, "sph neighbour state");
  if (dfsph) allocate_dfsph();
  // dfsph reads its solves' residuals every iteration: it steps one at a time (no blocks).
  // The second checkpoint lets run() record a block while the one before it is pending: in one
  // process, where both fit.
  const int kept =
      dfsph ? 0 : keeps_checkpoints(backend_, c, mask_sets, neighbor_state.valid(), ranks_ ? 1 : 2);
  for (int k = 0; k < kept; ++k) {
    SphBlockCheckpoint& cp = checkpoints[size_t(k)];
    cp.pos = real4("sph checkpoint positions");
    cp.vel = real4("sph checkpoint velocities");
    cp.accel = real4("sph checkpoint accelerations");
    cp.ids = backend_.create<uint32_t>(c, "sph checkpoint ids");
    cp.stats = backend_.create<uint32_t>(kSphStatWords, "sph checkpoint block stats");
  }
}

// The solves' buffers (sph_dfsph_scheme.h).
void SphDeviceState::allocate_dfsph() {
  auto real = [&](const char* label) { return backend_.create<Real>(capacity_, label); };
  factor = real("dfsph factor");
  kappa = real("dfsph kappa");
  kappa_density = real("dfsph density kappa sums");
  kappa_divergence = real("dfsph divergence kappa sums");
  kappa_density_t = real("dfsph sorted density kappa sums");
  kappa_divergence_t = real("dfsph sorted divergence kappa sums");
  residual = backend_.create<uint32_t>(kDfsphResidualWords, "dfsph residuals");
}

namespace {

// `b` with room for `count` elements, its contents kept.
template <class T>
void grow(Backend& backend, Buffer<T>& b, size_t count) {
  if (!b.valid() || b.size() >= count) return;
  Buffer<T> bigger = backend.create<T>(count, b.impl().label());
  backend.copy_bytes(b.impl(), bigger.impl(), b.impl().bytes());
  b = std::move(bigger);
}

}  // namespace

void SphDeviceState::reserve(uint32_t local, HashGrid& grid) {
  if (local <= capacity_) return;
  // A quarter more than asked, so that a rank whose share creeps up grows a few times only.
  capacity_ = uint32_t(std::min<uint64_t>(n_, uint64_t(local) + local / 4 + 1024));
  ++capacity_growths_;
  const size_t c = capacity_;
  for (Buffer<Real4>* b : {&pos, &vel, &xs, &vs, &sum_x, &sum_v, &ta, &tb, &tc, &accel})
    grow(backend_, *b, c);
  for (SphBlockCheckpoint& cp : checkpoints) {
    for (Buffer<Real4>* b : {&cp.pos, &cp.vel, &cp.accel}) grow(backend_, *b, c);
    grow(backend_, cp.ids, c);
  }
  for (Buffer<Real>* b : {&density, &pressure, &factor, &kappa, &kappa_density, &kappa_divergence,
                          &kappa_density_t, &kappa_divergence_t})
    grow(backend_, *b, c);
  for (Buffer<uint32_t>* b : {&ids, &ids_t, &grid.sorted_cells, &grid.sorted_index})
    grow(backend_, *b, c);
  grow(backend_, neighbor_rows, size_t(kSphRowMaskWords) * c);
  grow(backend_, reach_rows, size_t(kSphRowMaskWords) * c);
  grow(backend_, neighbor_state, size_t(kSphStateStride) * c);
}

}  // namespace masav
