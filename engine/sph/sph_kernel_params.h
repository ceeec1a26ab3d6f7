#pragma once
// Parameters and buffers of the SPH kernels declared in engine/core/backend.h (sph_density,
// sph_forces, sph_integrate). Plain data in double precision; the GPU backends round to fp32.
// The scene-level parameters (presets, integrators, time stepping) are in sph_params.h.
#include <cstdint>

#include "engine/core/buffer.h"
#include "engine/core/kernel_params.h"

namespace masav {

class DeviceApi;

enum class SphPressureModel : uint32_t {
  wcsph = 0,   // symmetric pressure force with the Tait equation of state (momentum-conserving)
  thesis = 1,  // thesis Eq. 4.5-4.7 as printed: density-difference pressure, not symmetric
};

// What the density and force kernels need. The particles are sorted by `grid` (cell size >= h,
// built by build_hash_grid); each kernel walks the 27 cells around the particle's cell at that
// build, so stage positions may drift from it by at most (cell_size - h) / 2.
struct SphStepParams {
  GridParams grid;
  uint32_t n = 0;                  // particles (== grid.n)
  uint32_t max_candidates = 8192;  // examined per particle; beyond it the kernel reports
  SphPressureModel model = SphPressureModel::wcsph;
  double h = 0.02;               // support radius (m)
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
  // Box walls as a continuum of fluid beyond them (wcsph only): adds their density and pressure
  // force to particles within h of a wall (see engine/kernels/sph_kernels.h, wall_density).
  bool walls = false;
  Vec3d box_min, box_max{1, 1, 1};
  // m: the wall continuum starts this far behind each wall, so that the first lattice layer
  // (dx/2 from the wall) has exactly rest density; see wall_offset_for_lattice.
  double wall_offset = 0.0;
};

// The sorted hash grid the SPH kernels walk.
struct SphGridView {
  const Buffer<uint32_t>* cells = nullptr;  // cell id of each sorted particle
  const Buffer<uint32_t>* cell_start = nullptr;
  const Buffer<uint32_t>* cell_end = nullptr;
};

// Per-step statistics the kernels accumulate in a small u32 buffer (kSphStatWords words,
// zero-filled before use): maxima of non-negative floats as their bit patterns (which order like
// the floats), "first index" words as the bitwise NOT of the smallest index (0 = none).
enum SphStat : uint32_t {
  kSphStatMaxCandidates = 0,  // most candidates any particle examined (density or forces)
  kSphStatOverflow = 1,       // ~(smallest sorted index over max_candidates)
  kSphStatNonFinite = 2,      // ~(smallest sorted index with a NaN/Inf result)
  kSphStatMaxSpeed2 = 3,      // float bits: largest |v|^2 written by sph_integrate
  kSphStatMaxAccel2 = 4,      // float bits: largest |a|^2 from sph_forces (particles that move)
  kSphStatMaxDisp2 = 5,       // float bits: largest |x_out - x0|^2 in sph_integrate
  kSphStatOutside = 6,        // particles outside the box after a step-ending stage
  kSphStatMaxNeighbors = 7,   // most neighbours within h (density kernel, itself included)
  kSphStatWords = 8
};

struct SphDensityIO {
  const Buffer<Real4>* positions = nullptr;  // sorted; xyz (m), w = inverse mass scale
  SphGridView grid;
  Buffer<Real>* density = nullptr;   // kg/m^3
  Buffer<Real>* pressure = nullptr;  // Pa
  Buffer<uint32_t>* stats = nullptr;
};

struct SphForcesIO {
  const Buffer<Real4>* positions = nullptr;
  const Buffer<Real4>* velocities = nullptr;  // the velocities the viscosity term uses
  const Buffer<Real>* density = nullptr;
  const Buffer<Real>* pressure = nullptr;
  SphGridView grid;
  Buffer<Real4>* accel = nullptr;  // xyz (m/s^2) with gravity and mass scale; w = neighbours
  Buffer<uint32_t>* stats = nullptr;
};

// Integrator stages; numbers match engine/kernels/sph_kernels.h (kOp*).
enum class SphStageOp : uint32_t {
  euler = 0,             // x1 = x0 + dt v0, v1 = v0 + dt a        (thesis Fig. 4.2)
  symplectic_euler = 1,  // v1 = v0 + dt a, x1 = x0 + dt v1        (Harada's update)
  rk4_stage1 = 2,        // classical RK4, thesis Eq. 4.8-4.12
  rk4_stage2 = 3,
  rk4_stage3 = 4,
  rk4_final = 5,
  kick_drift = 6,  // leapfrog: v_half = v0 + dt/2 a, x1 = x0 + dt v_half
  kick = 7,        // leapfrog: v1 = v_half + dt/2 a(x1)
};

struct SphIntegrateParams {
  uint32_t n = 0;
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

// Checked before any backend runs the kernel (engine/sph/sph_checks.cpp).
void validate(const DeviceApi& dev, const SphStepParams& p, const Buffer<Real4>& positions,
              const Buffer<uint32_t>& cells, const Buffer<uint32_t>& cell_start,
              const Buffer<uint32_t>& cell_end, const Buffer<Real>& density,
              const Buffer<Real>& pressure, const Buffer<uint32_t>& stats);
void validate(const DeviceApi& dev, const SphStepParams& p, const Buffer<Real4>& positions,
              const Buffer<Real4>& velocities, const Buffer<Real>& density,
              const Buffer<Real>& pressure, const Buffer<uint32_t>& cells,
              const Buffer<uint32_t>& cell_start, const Buffer<uint32_t>& cell_end,
              const Buffer<Real4>& accel, const Buffer<uint32_t>& stats);
void validate(const DeviceApi& dev, const SphIntegrateParams& p, const Buffer<Real4>* x0,
              const Buffer<Real4>& v0, const Buffer<Real4>* vk, const Buffer<Real4>& accel,
              const Buffer<Real4>* x_out, const Buffer<Real4>& v_out, const Buffer<Real4>* sum_x,
              const Buffer<Real4>* sum_v, const Buffer<uint32_t>& stats);

}  // namespace masav
