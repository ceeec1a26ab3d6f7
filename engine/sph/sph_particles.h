#pragma once
// Initial particles of a scene: the fluid block on a cubic lattice (exactly scene.particles,
// the top layer possibly partial), then the obstacle's particles at the fluid's rest spacing.
#include <cstdint>
#include <vector>

#include "engine/core/types.h"
#include "engine/sph/sph_params.h"

namespace masav {

struct SphParticles {
  std::vector<Vec4d> positions;   // m; w = inverse mass scale (1 fluid, 1/ratio, 0 pinned)
  std::vector<Vec4d> velocities;  // m/s
  uint32_t fluid = 0, obstacle = 0;
  double dx = 0;                   // rest spacing (m): the lattice at which density = rest density
  double placed_dx = 0;            // spacing the fluid was placed at (dx / density_ratio^(1/3))
  double h = 0;                    // support radius (m)
  double mass = 0;                 // SPH mass of every particle (kg)
  double gradient_correction = 1;  // 1 / spiky_gradient_moment(dx, h, dfsph)
  UVec3 lattice;                   // fluid lattice (x, y layers, z)
  uint32_t total() const { return fluid + obstacle; }
};

// The fluid's lattice, spacings and support radius and the obstacle's lattice of a scene, without
// placing a particle: what build_particles places, and what a restored state's counts and
// positions are checked against (sph_resume_checks.h) before anything of that size is built.
// Validates the scene (and the support against max_candidates).
struct SphSpacing {
  UVec3 lattice;   // fluid lattice (x, y layers, z)
  UVec3 obstacle;  // obstacle lattice; 0 x 0 x 0 without one
  double placed_dx = 0, dx = 0, h = 0;
  uint32_t fluid = 0;
  uint32_t obstacle_count() const { return obstacle.x * obstacle.y * obstacle.z; }
  uint32_t total() const { return fluid + obstacle_count(); }
};
SphSpacing sph_spacing(const SphScene& s);

SphParticles build_particles(const SphScene& s);

// The particle mass for which a particle inside a full cubic lattice of spacing dx has
// density rho0 with the poly6 kernel of support h (the thesis model's density), or with the
// spiky kernel (the wcsph and dfsph density), so a block at rest starts at rest density.
double lattice_mass(double rho0, double dx, double h, bool spiky = false);
// kappa = -1/3 sum_j (m/rho0) r_j W_spiky'(r_j) over the lattice of spacing dx (see
// SphStepParams::gradient_correction), m the lattice mass of the poly6 or (spiky) the spiky
// density; 1 for a continuum.
double spiky_gradient_moment(double dx, double h, bool spiky = false);

}  // namespace masav
