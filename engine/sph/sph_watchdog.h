#pragma once
// The stability watchdog of an SPH run, always on and independent of the CFL guard (which only
// chooses and splits dt): a run whose state leaves what a fluid of this scene can do stops with
// an Error naming the step, the time, the quantity, its value, the bound and a remedy.
//  - speed above max(2 c0, 2 sqrt(2 |g| D), 2 v0) (c0: the scene's speed of sound, D: the box
//    diagonal, v0: the fastest initial or set velocity): checked on the step statistics of every
//    step (a run() block that exceeds it is replayed step by step, so the message names the
//    very step);
//  - density above 2 max(rho0, the initial largest density) (wcsph; 3x for the thesis
//    model's isothermal gas): the same way;
//  - energy above the floor (kinetic + internal + potential over the lowest potential the box
//    allows) above its initial value by more than kEnergyMargin times that value (or times the
//    energy of the fluid's mass at 5% of c0, if larger): checked every kEnergyEvery steps on a
//    downloaded state (in run()'s blocks, read behind the block it ends together with the
//    block's stats, so the check waits for nothing); the run goes back to the last state that
//    passed (at most kEnergyEvery steps earlier). Gravity's work is part of the potential energy; a
//    scene has no inflow.
//  - a step that moves a particle (max speed x dt) further than the support radius h, past
//    neighbours whose forces it never saw: the same way. The CFL guard keeps steps far below
//    it; with the guard off, this is what stops a dt no pressure model can take (the thesis
//    model's energy check cannot: its isothermal gas has an expansion energy with no floor);
//  - a NaN or Inf: the guard's own check (sph_step_control.h), which names the particle.
#include <cstdint>
#include <string>

namespace masav {

struct SphState;
class SphSimulation;

struct SphWatchdog {
  // A viscous run only loses energy, and the wcsph force is the exact gradient of its stored
  // energy (an inviscid run gains about 1% at impacts, from the time step), but the thesis model
  // is not symmetric at all and gains tens of percent. The margin is therefore the whole
  // available energy: a doubled energy is a blow-up.
  static constexpr double kEnergyMargin = 1.0;
  static constexpr uint64_t kEnergyEvery = 128;
  double max_speed = 0;    // m/s
  double max_density = 0;  // kg/m^3
  double energy0 = 0;      // J: available energy of the baseline state
};

// Energy above the floor (J): kinetic + internal + potential - the potential of every moving
// particle at the box's lowest point under gravity.
double available_energy(const SphState& s, const SphSimulation& sim);

// The bounds for a run starting from `s` (speeds: the fastest of `s`).
SphWatchdog make_watchdog(const SphState& s, const SphSimulation& sim, double max_density);

// The remedy a watchdog message gives.
std::string watchdog_remedy();

}  // namespace masav
