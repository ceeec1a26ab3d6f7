#pragma once
// An SPH scene as data: the fluid block and an optional heavy obstacle, the fluid's constants
// and pressure model, the box, the integrator and time stepping. All in SI units (m, s, kg).
// Presets (sph_presets.h) fill it; the command line and, later, scene files override fields;
// validate() rejects bad values naming the field, the value and the allowed range.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "engine/kernels/sph_kernel_params.h"

namespace masav {

enum class SphIntegrator : uint8_t {
  euler,             // explicit (forward) Euler, thesis Fig. 4.2: first order
  symplectic_euler,  // v first, then x with the new v (Harada 2007's update): first order
  rk4,               // classical Runge-Kutta, thesis Eq. 4.8-4.12: fourth order, 4 force passes
  leapfrog,          // kick-drift-kick (velocity Verlet): second order, symplectic, 1 force pass
};

// What the CFL guard does when the step would be unstable (sph_step_control.h).
enum class SphCflGuard : uint8_t {
  reduce,  // split the step into smaller ones / retry a rejected step with a smaller dt
  stop,    // stop with an error that says which limit was exceeded and what to change
  off,     // take the step as asked (non-finite values still stop the run)
};

const char* to_string(SphIntegrator i);
const char* to_string(SphPressureModel m);
const char* to_string(SphCflGuard g);
// Parse user text; throw masav::Error naming `field` and the allowed values.
SphIntegrator parse_integrator(std::string_view s, std::string_view field = "integrator");
SphPressureModel parse_pressure_model(std::string_view s, std::string_view field = "pressure");
SphCflGuard parse_cfl_guard(std::string_view s, std::string_view field = "cfl_guard");

// A block of fluid filled with particles on a cubic lattice.
struct SphBlock {
  Vec3d min, max;              // extent as placed (m)
  Vec3d velocity;              // initial velocity (m/s)
  double density_ratio = 1.0;  // initial / rest density: > 1 starts compressed (explosion)
  // Start in hydrostatic equilibrium (wcsph, gravity along -y): each layer compressed by the
  // weight above it (Tait), so a resting fluid does not start with a compression wave.
  bool hydrostatic = false;
};

// Heavy obstacle particles (thesis §4.5.1): the fluid's SPH properties, a huge inertial mass.
struct SphObstacle {
  bool enabled = false;
  Vec3d min, max;           // m, filled at the fluid's rest spacing
  double mass_ratio = 1e6;  // inertial mass / fluid particle mass
  bool pinned = true;       // never moves (infinite mass)
};

struct SphScene {
  std::string preset = "custom";
  uint32_t particles = 32768;  // fluid particles (the obstacle adds its own)
  SphBlock block;
  SphObstacle obstacle;

  // Fluid.
  SphPressureModel model = SphPressureModel::wcsph;
  double rest_density = 1000.0;            // kg/m^3
  double h_over_dx = 2.0;                  // support radius / rest particle spacing
  std::optional<double> smoothing_radius;  // m; overrides h_over_dx when set
  double viscosity = 1e-3;                 // nu (m^2/s)
  double sound_speed = 20.0;               // c0 (m/s), wcsph
  double kp = 0.0;                         // thesis pressure constant (m^4 kg^-1 s^-2)
  bool clamp_negative_pressure = true;     // wcsph: no tension at free surfaces
  // dfsph: the solves stop once the mean residual over the moving particles is at most this
  // (relative: compression (rho*/rho0 - 1)^+, divergence dt (drho/dt)^+ / rho0), after at least
  // 2 (density) or 1 (divergence) and at most dfsph_max_iterations iterations (SPlisHSPlasH's
  // defaults: 0.01% and 0.1%).
  double dfsph_density_error = 1e-4;
  double dfsph_divergence_error = 1e-3;
  uint32_t dfsph_max_iterations = 100;
  Vec3d gravity{0.0, -9.81, 0.0};  // m/s^2 (y is up)

  // Box.
  Vec3d box_min{0, 0, 0}, box_max{1, 1, 1};  // m
  bool walls = true;
  double restitution = 0.3;
  double tangential_damping = 0.0;

  // Time stepping.
  // dfsph steps with its own scheme, a symplectic Euler step with its two solves: it takes
  // symplectic_euler only.
  SphIntegrator integrator = SphIntegrator::leapfrog;
  std::optional<double> dt;    // fixed step (s); unset: CFL-adaptive
  double cfl_velocity = 0.2;   // dt <= C h / (c + v_max)
  double cfl_force = 0.25;     // dt <= C sqrt(h / a_max)
  double cfl_viscous = 0.125;  // dt <= C h^2 / nu
  double dt_max = 5e-3;        // s, adaptive ceiling
  double dt_min = 1e-9;        // s: the guard stops below this
  SphCflGuard cfl_guard = SphCflGuard::reduce;
  double rk4_skin = 0.1;  // RK4: cells are h (1 + skin); stages may drift skin h / 2
  uint32_t max_candidates = 8192;

  uint64_t seed = 1;
  double jitter = 0.0;  // random offset of each particle, fraction of the spacing
};

// Throws masav::Error naming the first bad field.
void validate(const SphScene& s);

}  // namespace masav
