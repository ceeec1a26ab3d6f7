// Parameters of the SPH kernels (sph_density, sph_forces, sph_integrate): what the host
// describes (SphStepParams, SphIntegrateParams: the physics in double) and the layouts the
// kernels read (SphStepLayout, SphIntegrateLayout: coefficients computed once on the host, in the
// backend's precision). Layouts, enums and constants are shared by C++, CUDA and GLSL
// (engine/core/layout.h); scene-level parameters (presets, time stepping) are in
// engine/sph/sph_params.h.
#ifndef MASAV_KERNELS_SPH_KERNEL_PARAMS_H
#define MASAV_KERNELS_SPH_KERNEL_PARAMS_H
#include "engine/core/layout.h"

MASAV_NAMESPACE_BEGIN

MASAV_ENUM_BEGIN(SphPressureModel)
// symmetric pressure force with the Tait equation of state (momentum-conserving)
MASAV_ENUMERATOR(SphPressureModel, wcsph, 0)
// thesis Eq. 4.5-4.7 as printed: density-difference pressure, not symmetric
MASAV_ENUMERATOR(SphPressureModel, thesis, 1)
// divergence-free SPH (Bender & Koschier): incompressibility by two iterative pressure solves
// per step (engine/kernels/dfsph_kernels.h); the force kernel adds viscosity and gravity only
MASAV_ENUMERATOR(SphPressureModel, dfsph, 2)
MASAV_ENUM_END(SphPressureModel)

// Integrator stages (sph::integrate_stage in engine/kernels/sph_integrate_body.h).
MASAV_ENUM_BEGIN(SphStageOp)
MASAV_ENUMERATOR(SphStageOp, euler, 0)             // x1 = x0 + dt v0, v1 = v0 + dt a (Fig. 4.2)
MASAV_ENUMERATOR(SphStageOp, symplectic_euler, 1)  // v1 = v0 + dt a, x1 = x0 + dt v1 (Harada)
MASAV_ENUMERATOR(SphStageOp, rk4_stage1, 2)        // classical RK4, thesis Eq. 4.8-4.12
MASAV_ENUMERATOR(SphStageOp, rk4_stage2, 3)
MASAV_ENUMERATOR(SphStageOp, rk4_stage3, 4)
MASAV_ENUMERATOR(SphStageOp, rk4_final, 5)
MASAV_ENUMERATOR(SphStageOp, kick_drift, 6)  // leapfrog: v_half = v0 + dt/2 a, x1 = x0 + dt v_half
MASAV_ENUMERATOR(SphStageOp, kick, 7)        // leapfrog: v1 = v_half + dt/2 a(x1)
MASAV_ENUMERATOR(SphStageOp, accelerate, 8)  // dfsph: v1 = v0 + dt a (positions untouched)
MASAV_ENUMERATOR(SphStageOp, drift, 9)       // dfsph: x1 = x0 + dt v0, v1 = v0, then the walls
MASAV_ENUM_END(SphStageOp)

// Per-step statistics the kernels accumulate in a small u32 buffer (kSphStatWords words,
// zero-filled before use): maxima of non-negative floats as their bit patterns (which order like
// the floats), "first index" words as the bitwise NOT of the smallest index (0 = none).
MASAV_CONSTANT(kSphStatMaxCandidates, 0)  // most candidates any particle examined
MASAV_CONSTANT(kSphStatOverflow, 1)       // ~(smallest sorted index over max_candidates)
MASAV_CONSTANT(kSphStatNonFinite, 2)      // ~(smallest sorted index with a NaN/Inf result)
MASAV_CONSTANT(kSphStatMaxSpeed2, 3)      // float bits: largest |v|^2 written by sph_integrate
MASAV_CONSTANT(kSphStatMaxAccel2, 4)      // float bits: largest |a|^2 from sph_forces (movers)
MASAV_CONSTANT(kSphStatMaxDisp2, 5)       // float bits: largest |x_out - x0|^2 in sph_integrate
MASAV_CONSTANT(kSphStatOutside, 6)        // particles outside the box after a step-ending stage
MASAV_CONSTANT(kSphStatMaxNeighbors, 7)   // most neighbours within h (density, itself included)
MASAV_CONSTANT(kSphStatMaxDensity, 8)     // float bits: largest density from sph_density
MASAV_CONSTANT(kSphStatWords, 9)

// SphIntegrateLayout::dt_slot of a dt passed inline (in `dt`). A backend that replays recorded
// work (Vulkan, DeviceApi::begin_capture) passes a captured stage's dt through a table instead,
// at dt_slot, so that blocks differing only in dt replay one recording.
MASAV_CONSTANT(kSphDtInline, 0xFFFFFFFFu)

// Neighbour row masks (sph_density's optional output, sph_forces' optional input): for each of
// the 9 rows of a particle's 27-cell walk, 64 bits, bit b set when candidate first + b of the
// row lies within h (the particle itself included); a row of more candidates has no bits and
// sph_forces walks it candidate by candidate. Word w = 2 row + half (low half first) of sorted
// particle i is neighbor_rows[w n + i]: structure of arrays, so neighbouring invocations read
// neighbouring words. Formats and walks: engine/kernels/sph_kernels.h (RowMasks).
MASAV_CONSTANT(kSphRowMaskBits, 64)
MASAV_CONSTANT(kSphRowMaskWords, 18)

// The neighbour state (sph_density's optional output, sph_forces' optional input): what the
// force walk reads of a particle, as two Real4 per sorted particle i, side by side:
// neighbor_state[2 i] = (x, y, z, density), [2 i + 1] = (vx, vy, vz, p / rho^2). The walk tests a
// candidate's distance with the first and reads the second only for a neighbour within h: one
// 32-byte record per neighbour instead of positions, velocities, density and pressure (four
// arrays), and p / rho^2 (sph::pressure_over_rho2) computed once per particle, not per pair.
MASAV_CONSTANT(kSphStateStride, 2)

// Reach masks: sph_density's masks (the format above) of the candidates within a reach radius
// R >= h, in a buffer of their own (reach_rows). RK4 sorts once per step into cells of
// h + skin, and no particle drifts more than skin / 2 from the sorted positions within the step
// (SphSimulation rejects a step that drifts further), so every pair within h at a later stage was
// within h + skin <= R at the first: the first evaluation records the masks and the later three
// walk only their bits instead of every candidate of the 27 inflated cells.
MASAV_ENUM_BEGIN(SphReach)
MASAV_ENUMERATOR(SphReach, none, 0)    // reach_rows unused
MASAV_ENUMERATOR(SphReach, record, 1)  // the walk visits every candidate and writes reach_rows
MASAV_ENUMERATOR(SphReach, walk, 2)    // the walk visits only reach_rows' bits (rows that fit)
MASAV_ENUM_END(SphReach)

// What sph_density and sph_forces read: the grid they walk and the smoothing kernels' constants
// (definitions: device_params below; formulas: engine/kernels/sph_kernels.h).
MASAV_REAL_LAYOUT(SphStepLayout) {
  uvec3 dims;           // the hash grid's cells per axis
  uint n;               // particles
  uint max_candidates;  // examined per particle; beyond it the kernel reports an overflow
  MASAV_ENUM(SphPressureModel) model;
  uint clamp_negative_pressure;
  uint walls;  // box walls as mirror images (wcsph only; sph::WallMirrors)
  real_t h2;
  real_t inv_h;
  real_t inv_h2;
  real_t density;  // m * 15 / (pi h^3) (spiky); thesis: m * 315 / (64 pi h^3) (poly6)
  // wcsph: m * 45 / (pi h^4) / kappa; thesis: kp * m * 45 / (pi h^3) / 2; dfsph: m * 45 / (pi h^4)
  real_t pressure;
  real_t viscosity;  // nu * m * 45 / (pi h^5)
  real_t rest_density;
  real_t inv_rest_density;
  real_t eos;  // wcsph: Tait B = rho0 c0^2 / 7 (Pa); thesis: c^2 of the reported pressure; dfsph: 0
  real_t gravity[3];
  real_t lo[3];
  real_t hi[3];
  // 1 when the call passes neighbor_rows: a shader cannot tell a missing optional buffer from
  // the one Vulkan binds in its place (C++ and CUDA test the pointer instead).
  uint neighbor_rows;
  // The particles computed: [first, end) of the n (SphStepParams::first, count).
  uint first;
  uint end;
  MASAV_ENUM(SphReach) reach;  // sph_density only
  real_t reach2;               // R^2 of the reach masks (SphReach::record)
};

// What sph_integrate reads: one stage of the integrator, then the box walls.
MASAV_REAL_LAYOUT(SphIntegrateLayout) {
  MASAV_ENUM(SphStageOp) op;
  uint walls;
  uint n;
  real_t dt;
  real_t lo[3];
  real_t restitution;
  real_t hi[3];
  real_t tangential_damping;
  uint first;  // the particles stepped: [first, end) of the n
  uint end;
  uint dt_slot;  // kSphDtInline: dt is `dt`; else the Vulkan replay table's entry (see above)
};

MASAV_NAMESPACE_END

#ifdef __cplusplus
#include <cmath>
#include <tuple>

#include "engine/core/buffer.h"
#include "engine/kernels/grid_params.h"

namespace masav {

// At most 128 bytes: the most push constants every Vulkan device takes (vk_kernels.cpp asserts
// it). One check takes at most 20 fields (engine/core/pp.h): SphStepLayout's take two.
MASAV_LAYOUT_CHECK(SphStepLayout<float>, 128, (dims, 0), (n, 12), (max_candidates, 16), (model, 20),
                   (clamp_negative_pressure, 24), (walls, 28), (h2, 32), (inv_h, 36), (inv_h2, 40),
                   (density, 44), (pressure, 48), (viscosity, 52), (rest_density, 56),
                   (inv_rest_density, 60), (eos, 64), (gravity, 68), (lo, 80), (hi, 92),
                   (neighbor_rows, 104))
MASAV_LAYOUT_CHECK(SphStepLayout<float>, 128, (first, 108), (end, 112), (reach, 116), (reach2, 120))
MASAV_LAYOUT_CHECK(SphIntegrateLayout<float>, 64, (op, 0), (walls, 4), (n, 8), (dt, 12), (lo, 16),
                   (restitution, 28), (hi, 32), (tangential_damping, 44), (first, 48), (end, 52),
                   (dt_slot, 56))

// SphStepParams / SphIntegrateParams::count for "from first to n".
inline constexpr uint32_t kSphAllParticles = UINT32_MAX;

// What the density and force kernels need. The particles are sorted by `grid` (cell size >= h,
// built by build_hash_grid); each kernel walks the 27 cells around the particle's cell at that
// build, so stage positions may drift from it by at most (cell_size - h) / 2.
struct SphStepParams {
  GridParams grid;
  uint32_t n = 0;  // particles (== grid.n)
  // The particles the kernel computes: [first, first + count) of the n; the others are only
  // read, as neighbours (a rank's halo, engine/sph/sph_ranks.h). count kSphAllParticles: from
  // first to n.
  uint32_t first = 0;
  uint32_t count = kSphAllParticles;
  uint32_t max_candidates = 8192;  // examined per particle; beyond it the kernel reports
  SphPressureModel model = SphPressureModel::wcsph;
  double h = 0.02;  // support radius (m)
  // sph_density's reach masks (SphReach above) and their radius R (m): h <= R <= the grid's
  // cell size, so that the 27 cells hold every candidate within R.
  SphReach reach = SphReach::none;
  double reach_radius = 0.0;
  double mass = 0.008;           // SPH mass of every particle (kg)
  double rest_density = 1000.0;  // rho0 (kg/m^3)
  double sound_speed = 20.0;     // c0 (m/s): Tait B = rho0 c0^2 / 7 (wcsph)
  bool clamp_negative_pressure = true;
  // wcsph: the pressure force's scale 1/kappa, kappa = -1/3 sum_j (m/rho0) r_j W'(r_j) over the
  // rest lattice (1 for a continuum; 0.947 for the spiky kernel at h = 2 dx): a linear pressure
  // field then gives exactly its gradient on the lattice, so a column at rest balances gravity.
  double gradient_correction = 1.0;
  double kp = 0.0;                 // thesis pressure constant (m^4 kg^-1 s^-2)
  double viscosity = 0.0;          // nu (m^2/s)
  Vec3d gravity{0.0, -9.81, 0.0};  // m/s^2
  // Box walls as mirror images of the fluid near them (wcsph only): their density, pressure and
  // no-slip viscous terms (see engine/kernels/sph_kernels.h, WallMirrors).
  bool walls = false;
  Vec3d box_min, box_max{1, 1, 1};
};

// The sorted hash grid the SPH kernels walk.
struct SphGridView {
  const Buffer<uint32_t>* cells = nullptr;  // cell id of each sorted particle
  const Buffer<uint32_t>* cell_start = nullptr;
  const Buffer<uint32_t>* cell_end = nullptr;
  // Whether the tables are the counting build's (HashGrid::prefix_ranges): the kernels read a
  // row of 3 cells as [start of the first, end of the last), so they refuse other tables.
  bool prefix_ranges = false;
};

struct SphDensityIO {
  const Buffer<Real4>* positions = nullptr;  // sorted; xyz (m), w = inverse mass scale
  SphGridView grid;
  Buffer<Real>* density = nullptr;   // kg/m^3
  Buffer<Real>* pressure = nullptr;  // Pa
  Buffer<uint32_t>* stats = nullptr;
  // Optional: the neighbour row masks (kSphRowMaskWords n words) for a later sph_forces on the
  // same positions, grid and h.
  Buffer<uint32_t>* neighbor_rows = nullptr;
  // The reach masks (kSphRowMaskWords n words), written or read as SphStepParams::reach says.
  Buffer<uint32_t>* reach_rows = nullptr;
  // Optional: the neighbour state (kSphStateStride n elements, see kSphStateStride) of the
  // particles computed, for a later sph_forces on the same positions and grid; it needs the
  // velocities the viscosity term will use.
  const Buffer<Real4>* velocities = nullptr;
  Buffer<Real4>* neighbor_state = nullptr;
};

struct SphForcesIO {
  const Buffer<Real4>* positions = nullptr;
  const Buffer<Real4>* velocities = nullptr;  // the velocities the viscosity term uses
  const Buffer<Real>* density = nullptr;
  const Buffer<Real>* pressure = nullptr;
  SphGridView grid;
  Buffer<Real4>* accel = nullptr;  // xyz (m/s^2) with gravity and mass scale; w = neighbours
  Buffer<uint32_t>* stats = nullptr;
  // Optional: the masks sph_density wrote for these positions, grid and h. The result is the
  // same as without them (on Vulkan up to the order of summation: see sph_forces.comp).
  const Buffer<uint32_t>* neighbor_rows = nullptr;
  // Optional: sph_density's neighbour state for these positions, velocities and grid, written
  // for every particle the walk can reach; read in place of positions' xyz, velocities, density
  // and pressure (positions' w, the inverse mass, is still read). The same result bit for bit.
  const Buffer<Real4>* neighbor_state = nullptr;
};

struct SphIntegrateParams {
  uint32_t n = 0;
  // The particles the kernel computes: [first, first + count) of the n; the others are only
  // read, as neighbours (a rank's halo, engine/sph/sph_ranks.h). count kSphAllParticles: from
  // first to n.
  uint32_t first = 0;
  uint32_t count = kSphAllParticles;
  SphStageOp op = SphStageOp::euler;
  double dt = 1e-4;  // s
  bool walls = true;
  Vec3d box_min, box_max{1, 1, 1};
  double restitution = 0.5;         // normal velocity kept (reversed) at a wall, in [0, 1]
  double tangential_damping = 0.0;  // tangential velocity removed at a wall, in [0, 1]
};

// Buffers of one stage; unused ones may be null. Output buffers may be the same as inputs read
// at the same index (each particle reads its own element before writing it).
struct SphIntegrateIO {
  const Buffer<Real4>* x0 = nullptr;     // step-start positions (w = inverse mass, kept)
  const Buffer<Real4>* v0 = nullptr;     // step-start velocities (kick: v_half)
  const Buffer<Real4>* vk = nullptr;     // RK4 stages 2-4: velocity of the stage state
  const Buffer<Real4>* accel = nullptr;  // acceleration of the stage state
  Buffer<Real4>* x_out = nullptr;        // not written by kick
  Buffer<Real4>* v_out = nullptr;
  Buffer<Real4>* sum_x = nullptr;  // RK4 running sums; unused otherwise
  Buffer<Real4>* sum_v = nullptr;  // RK4 running sums; kick_drift: predicted v1
  Buffer<uint32_t>* stats = nullptr;
};

// One past the last particle a kernel computes, and how many it computes.
template <class P>
uint32_t sph_range_end(const P& p) {
  return p.count == kSphAllParticles ? p.n : p.first + p.count;
}
template <class P>
uint32_t sph_range_count(const P& p) {
  const uint32_t end = sph_range_end(p);
  return end > p.first ? end - p.first : 0u;
}

// Signal speed of the pressure model (m/s): c0 for wcsph; for the thesis model, whose force
// kp m sum (rho_j - rho_i)/(2 rho_j) grad W_thesis approximates -(3/14) kp h grad rho (the
// continuum moment of Eq. 4.7's kernel), the sound speed of that isothermal gas,
// sqrt(3/14 kp rho0 h); 0 for dfsph, whose solves replace the sound waves. Used by the CFL limit
// and to report a thesis-model pressure c^2 (rho - rho0).
inline double signal_speed(const SphStepParams& p) {
  if (p.model == SphPressureModel::dfsph) return 0.0;  // incompressible: no sound to resolve
  if (p.model == SphPressureModel::thesis)
    return std::sqrt(3.0 / 14.0 * p.kp * p.rest_density * p.h);
  return p.sound_speed;
}

// Whether a call of sph_density or sph_forces passes the neighbour row masks: their last buffer
// (kernels.inc), null when not given.
template <class... Buffers>
bool passes_neighbor_rows(const Buffers&... buffers) {
  if constexpr (sizeof...(Buffers) == 0)
    return false;
  else
    return std::get<sizeof...(Buffers) - 1>(std::tie(buffers...)) != nullptr;
}

// The layouts the kernels read: every coefficient computed in double, then rounded once to the
// backend's precision F (double on the CPU reference, float elsewhere), so that every backend
// starts from the same values.
template <class F, class... Buffers>
SphStepLayout<F> device_params(const SphStepParams& p, const Buffers&... buffers) {
  constexpr double pi = 3.14159265358979323846;
  const double h = p.h;
  const bool thesis = p.model == SphPressureModel::thesis;
  const double cs = signal_speed(p);
  SphStepLayout<F> c{};
  c.dims = p.grid.dims;
  c.n = p.n;
  c.max_candidates = p.max_candidates;
  c.model = p.model;
  c.clamp_negative_pressure = p.clamp_negative_pressure ? 1u : 0u;
  c.walls = p.walls && !thesis ? 1u : 0u;
  c.h2 = F(h * h);
  c.inv_h = F(1.0 / h);
  c.inv_h2 = F(1.0 / (h * h));
  const bool dfsph = p.model == SphPressureModel::dfsph;
  c.density =
      F(!thesis ? p.mass * 15.0 / (pi * h * h * h) : p.mass * 315.0 / (64.0 * pi * h * h * h));
  c.pressure = F(thesis  ? p.kp * p.mass * 45.0 / (pi * h * h * h) / 2.0
                 : dfsph ? p.mass * 45.0 / (pi * h * h * h * h)
                         : p.gradient_correction * p.mass * 45.0 / (pi * h * h * h * h));
  c.viscosity = F(p.viscosity * p.mass * 45.0 / (pi * std::pow(h, 5)));
  c.rest_density = F(p.rest_density);
  c.inv_rest_density = F(1.0 / p.rest_density);
  c.eos = F(thesis ? cs * cs : dfsph ? 0.0 : p.rest_density * p.sound_speed * p.sound_speed / 7.0);
  const double g[3] = {p.gravity.x, p.gravity.y, p.gravity.z};
  const double lo[3] = {p.box_min.x, p.box_min.y, p.box_min.z};
  const double hi[3] = {p.box_max.x, p.box_max.y, p.box_max.z};
  for (int a = 0; a < 3; ++a) {
    c.gravity[a] = F(g[a]);
    c.lo[a] = F(lo[a]);
    c.hi[a] = F(hi[a]);
  }
  c.neighbor_rows = passes_neighbor_rows(buffers...) ? 1u : 0u;
  c.first = p.first;
  c.end = sph_range_end(p);
  c.reach = p.reach;
  c.reach2 = F(p.reach_radius * p.reach_radius);
  return c;
}

template <class F, class... Buffers>
SphIntegrateLayout<F> device_params(const SphIntegrateParams& p, const Buffers&...) {
  SphIntegrateLayout<F> s{};
  s.op = p.op;
  s.walls = p.walls ? 1u : 0u;
  s.n = p.n;
  s.dt = F(p.dt);
  const double lo[3] = {p.box_min.x, p.box_min.y, p.box_min.z};
  const double hi[3] = {p.box_max.x, p.box_max.y, p.box_max.z};
  for (int a = 0; a < 3; ++a) {
    s.lo[a] = F(lo[a]);
    s.hi[a] = F(hi[a]);
  }
  s.restitution = F(p.restitution);
  s.tangential_damping = F(p.tangential_damping);
  s.first = p.first;
  s.end = sph_range_end(p);
  s.dt_slot = kSphDtInline;
  return s;
}

class DeviceApi;
// Checked before any backend runs the kernel (engine/kernels/sph_checks.cpp).
void validate(const DeviceApi& dev, const SphStepParams& p, const Buffer<Real4>& positions,
              const Buffer<uint32_t>& cells, const Buffer<uint32_t>& cell_start,
              const Buffer<uint32_t>& cell_end, const Buffer<Real>& density,
              const Buffer<Real>& pressure, const Buffer<uint32_t>& stats,
              const Buffer<Real4>* velocities, const Buffer<Real4>* neighbor_state,
              const Buffer<uint32_t>* reach_rows, const Buffer<uint32_t>* neighbor_rows);
void validate(const DeviceApi& dev, const SphStepParams& p, const Buffer<Real4>& positions,
              const Buffer<Real4>& velocities, const Buffer<Real>& density,
              const Buffer<Real>& pressure, const Buffer<uint32_t>& cells,
              const Buffer<uint32_t>& cell_start, const Buffer<uint32_t>& cell_end,
              const Buffer<Real4>& accel, const Buffer<uint32_t>& stats,
              const Buffer<Real4>* neighbor_state, const Buffer<uint32_t>* neighbor_rows);
void validate(const DeviceApi& dev, const SphIntegrateParams& p, const Buffer<Real4>* x0,
              const Buffer<Real4>& v0, const Buffer<Real4>* vk, const Buffer<Real4>& accel,
              const Buffer<Real4>* x_out, const Buffer<Real4>& v_out, const Buffer<Real4>* sum_x,
              const Buffer<Real4>* sum_v, const Buffer<uint32_t>& stats);

}  // namespace masav
#endif
#endif
