#pragma once
// The thesis's scenes as data (Figures 4.10-4.13, §4.5.1), in SI units, plus the dam break used
// to compare with laboratory measurements. Each preset fills a whole SphScene for a given
// particle count; callers override fields afterwards.
//
// Thesis constants -> SI. The thesis gives nu ("dynamic viscosity constant") and kp ("pressure
// constant") per figure without units. We read them in the unit system of the CUDA SDK
// "particles" sample the thesis built on: length unit l = half the tank (its world is
// [-1, 1]^3), time unit tau fixed by the SDK's gravity (0.0003 l/tau^2 = 9.81 m/s^2). nu is
// then a kinematic viscosity, nu_SI = nu * l^2 / tau (l = 0.5 m: x 63.9 m^2/s). kp cannot be
// mapped the same way: Eq. 4.7's gradient as printed has (r_e - r)^3, one length too many, so
// kp's unit depends on h. The thesis force is that of an isothermal gas (a = -(c^2/rho) grad rho
// with c^2 = 3/14 kp rho0 h, see signal_speed), which under gravity settles with a scale height
// proportional to kp h / g. We calibrate one scale (kThesisKpScale) so that the thesis water --
// the 0.4 m cube dropped into the 1 m tank -- settles as a pool like the 6.4 cm one it would
// form at rest density: centre of mass ~3.2 cm above the floor at the default h = 2.5 cm
// (measured: kp = 0.5 at h = 5 cm, 4,096 particles, gives 3.7 cm after 2.5 s; kp = 1 at
// h = 2.5 cm), and keep the thesis's ratios between the presets. The
// explosion's kp is 1/116 of the water's: in the thesis model it cannot hold itself up against
// gravity and spreads over the floor (the wcsph explosion bursts). See README ("SPH fluid").
#include <string>
#include <string_view>
#include <vector>

#include "engine/sph/sph_params.h"

namespace masav {

// Thesis constants (Figures 4.10-4.13).
struct ThesisConstants {
  double nu;  // "dynamic viscosity constant"
  double kp;  // "pressure constant"
};
constexpr ThesisConstants kThesisExplosion{5.37e-9, 1.22e-7};  // Fig. 4.10
constexpr ThesisConstants kThesisWater{5.35e-5, 1.41e-5};      // Figs. 4.11-4.12
constexpr ThesisConstants kThesisMud{3.73e-4, 1.50e-5};        // Fig. 4.13

constexpr double kThesisViscosityScale = 63.94;  // m^2/s per thesis unit: l^2 / tau, l = 0.5 m
constexpr double kThesisKpScale = 7.0e4;         // m^4 kg^-1 s^-2 per thesis unit (calibrated)

struct SphPresetInfo {
  std::string name;
  std::string description;
};
const std::vector<SphPresetInfo>& sph_presets();

// Throws masav::Error naming `preset` and the known names for an unknown one.
SphScene make_preset(std::string_view name, uint32_t particles = 32768);

// The largest compression the gravity-driven presets (water, mud, dam-break, obstacle) set their
// speed of sound for. A weakly compressible fluid that hits a wall at speed v compresses by about
// v / c0 there (the water hammer), so c0 = v_fall / this, v_fall being the fastest speed the
// fluid can reach by falling. 0.1 is Mach 0.1: well under 1% in the flow, up to ~8% in single
// particles at the impacts (measured: README, "Compression you choose").
constexpr double kPresetMaxCompression = 0.1;
constexpr double kMinMaxCompression = 0.001;
constexpr double kMaxMaxCompression = 0.5;

// Sets a gravity-driven preset's c0 for `max_compression` (in [0.001, 0.5]) at its impacts.
// Throws masav::Error naming `field` for a value out of range or for the explosion, whose speeds
// come from its own compressed gas and scale with c0.
void set_max_compression(SphScene& s, double max_compression, const std::string& field);

}  // namespace masav
