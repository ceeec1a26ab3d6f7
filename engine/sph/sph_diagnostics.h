#pragma once
// Whole-fluid diagnostics from a downloaded state, in double precision on the host: energies,
// momentum, centre of mass, density statistics and the dam break's surge front.
#include <string>
#include <vector>

#include "engine/sph/sph_simulation.h"

namespace masav {

struct SphDiagnostics {
  double kinetic = 0;    // J, sum 1/2 M v^2 over particles that move (M = inertial mass)
  double potential = 0;  // J, -sum M g . x over particles that move
  // J, sum m e(rho): wcsph's Tait energy; thesis: c^2 ln(rho/rho0); dfsph: 0 (incompressible)
  double internal = 0;
  double total() const { return kinetic + potential + internal; }
  Vec3d momentum;             // kg m/s, sum M v
  double momentum_scale = 0;  // kg m/s, sum M |v| (what momentum errors are relative to)
  Vec3d center_of_mass;       // m, of the fluid particles
  double mean_density = 0, max_density = 0;  // kg/m^3, fluid particles
  // Compression max(rho / rho0 - 1, 0) of the fluid particles, mean and largest: how
  // compressible the run is (weakly compressible SPH aims at ~1%). Below rest density does not
  // count: particles near a free surface read low densities from their missing neighbours.
  double mean_compression = 0, max_compression = 0;
  // Its 99.9th percentile: the largest but the top 0.1% of the fluid particles (an impact peak of
  // one particle for a few steps is max_compression, not this).
  double p999_compression = 0;
  double max_speed = 0;    // m/s
  double surge_front = 0;  // m: the fluid's largest x, plus half a spacing (the particle's extent)
  uint32_t outside = 0;    // particles outside the box (by more than 1e-6 of a coordinate)
  bool finite = true;      // every position and velocity finite
};

SphDiagnostics compute_diagnostics(const SphState& s, const SphSimulation& sim);

// Per-step CSV diagnostics: one row per recorded step.
std::vector<std::string> diagnostics_columns();
std::vector<double> diagnostics_row(const SphSimulation& sim, const SphDiagnostics& d);

}  // namespace masav
