#pragma once
// Sampling tables for orbital_sample, built in double on the host.
//
// Exact placement. |psi|^2 dV = [r^2 R_nl^2 dr] [Pbar_l^|m|(x)^2 dx] [azimuthal factor dphi] is a
// product of three independent one-dimensional densities, so a particle is (r, cos theta, phi)
// with each coordinate drawn from its own inverse CDF. Each factor's CDF is tabulated on a uniform
// grid of bins; each bin's mass is integrated with 8-point Gauss-Legendre (relative error < 1e-14
// for these smooth factors) and the running sums are rounded to integers out of 2^24 -- the
// resolution of the 24-bit uniforms the kernel draws. The kernel finds the bin of its integer
// uniform by a bounded binary search (exact, identical on every backend) and places the particle
// uniformly inside the bin. The sampled law is therefore |psi|^2 with three approximations:
//   - each bin's mass is exact up to 2^-24 (the uniforms' own resolution);
//   - inside a bin the density is flat instead of |psi|^2: with 4096 radial bins this moves <r> by
//     about h^2/12 * max|f'/f| (h = bin width), below 1e-5 relative for every state n <= 16;
//   - the radial tail beyond radial_max_a0 (mass <= tail_mass, default 1e-12) is cut.
// None is visible against the sampling noise of fewer than 10^9 particles.
//
// Shell placement (thesis Algorithm 2.1, `placement = shells`): sites on shells of width dr, cells
// uniform in cos theta and phi; each site gets its expected count count * P(cell), rounded
// systematically (running sums rounded, so the total is exactly `count`), jittered uniformly in
// the cell's volume.
// A stratified, piecewise-constant approximation of |psi|^2: its error is that of the site grid.
#include <cstdint>
#include <vector>

#include "engine/atom/orbital.h"
#include "engine/kernels/atom_params.h"

namespace masav::atom {

struct TableOptions {
  uint32_t radial_bins = 4096;
  uint32_t polar_bins = 2048;
  uint32_t azimuth_bins = 1024;
  double tail_mass = 1e-12;
  // Shell placement: sites per dimension (shells x polar cells x azimuthal cells).
  uint32_t shells = 200;
  uint32_t shell_polar = 48;
  uint32_t shell_azimuth = 96;
};

struct OrbitalTables {
  OrbitalSampleParams params;  // the geometry; count and seed as given
  std::vector<uint32_t> cdf;
  double truncated_mass = 0;  // radial mass beyond radial_max_a0
};

OrbitalTables make_orbital_tables(const OrbitalState& s, OrbitalPlacement placement, uint32_t count,
                                  uint64_t seed, const TableOptions& o = {});

// r such that the probability of |x| <= r is `p` (p < 1 - 1e-12).
double radial_quantile(const OrbitalState& s, double p);
// Half-width of the cube centred on the nucleus that holds >= `p` of the probability (the sphere
// of radius radial_quantile(p) fits inside it).
double box_half_width(const OrbitalState& s, double p = 0.999);

// Exact probability that r lies in [a, b] (tests and benchmarks).
double radial_probability(const OrbitalState& s, double a, double b);
// Exact probability that cos theta lies in [a, b].
double polar_probability(const OrbitalState& s, double a, double b);

}  // namespace masav::atom
