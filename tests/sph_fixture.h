#pragma once
// Particles for the SPH kernel tests: a jittered lattice (density varies by ~10%) with random
// velocities, sorted into a hash grid on a backend, and the kernels' parameters. The same seed
// gives the same particles, cells and sorted order on every backend.
#include <doctest/doctest.h>

#include <algorithm>
#include <bit>
#include <random>
#include <string>
#include <vector>

#include "engine/grid/hash_grid.h"
#include "engine/kernels/backend.h"
#include "engine/kernels/sph_kernel_params.h"
#include "engine/kernels/sph_kernels.h"
#include "engine/sph/sph_case_buffers.h"
#include "engine/sph/sph_particles.h"

namespace masav::test {

// Whether backend b computes the SPH kernels in fp32: a GPU, or the CPU backend's fp32 path.
inline bool sph_in_fp32(const Backend& b) {
  return !b.caps().real_is_double || b.caps().sph_pairs_fp32;
}

struct SphCase {
  std::vector<Vec4f> positions;  // w: inverse mass (some pinned / heavy particles)
  std::vector<Vec4f> velocities;
  SphStepParams params;
  double dx = 0;
};

inline SphCase make_sph_case(uint32_t side, SphPressureModel model, uint64_t seed,
                             double jitter = 0.3) {
  SphCase c;
  c.dx = 0.01;
  const double h = 2.0 * c.dx;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (uint32_t z = 0; z < side; ++z)
    for (uint32_t y = 0; y < side; ++y)
      for (uint32_t x = 0; x < side; ++x) {
        const float inv_mass = (x + y + z) % 37 == 0 ? 0.0f : ((x * y) % 29 == 1 ? 1e-3f : 1.0f);
        c.positions.push_back({float(0.05 + (x + jitter * u(rng)) * c.dx),
                               float(0.05 + (y + jitter * u(rng)) * c.dx),
                               float(0.05 + (z + jitter * u(rng)) * c.dx), inv_mass});
        c.velocities.push_back(
            {float(0.3 * u(rng)), float(0.3 * u(rng)), float(0.3 * u(rng)), 0.0f});
      }
  const uint32_t n = uint32_t(c.positions.size());
  const float cell = float(h);
  const uint32_t cells = uint32_t(std::ceil((0.1 + side * c.dx) / double(cell)));
  SphStepParams& p = c.params;
  p.grid = make_grid_params({0, 0, 0}, std::nextafter(cell, 1.0f), {cells, cells, cells}, n);
  p.n = n;
  p.model = model;
  p.h = h;
  p.mass = lattice_mass(1000.0, c.dx, h);
  p.rest_density = 1000.0;
  p.sound_speed = 15.0;
  p.kp = 5.0;
  p.viscosity = 2e-3;
  p.gravity = {0.0, -9.81, 0.0};
  return c;
}

// Box walls just around the particles (their images reach every particle within h of a wall;
// none is outside, as the integrator guarantees in a run), 1-3 mm away, different per axis.
inline void with_walls(SphCase& c, bool on) {
  c.params.walls = on;
  Vec3d lo{1e9, 1e9, 1e9}, hi{-1e9, -1e9, -1e9};
  for (const Vec4f& x : c.positions) {
    lo = {std::min(lo.x, double(x.x)), std::min(lo.y, double(x.y)), std::min(lo.z, double(x.z))};
    hi = {std::max(hi.x, double(x.x)), std::max(hi.y, double(x.y)), std::max(hi.z, double(x.z))};
  }
  c.params.box_min = {lo.x - 0.001, lo.y - 0.002, lo.z - 0.003};
  c.params.box_max = {hi.x + 0.003, hi.y + 0.001, hi.z + 0.002};
}

// Runs body(c) on the side^3 case of `seed` for each pressure model, without and with walls,
// the variant captured for a failing check's message.
template <class Body>
void for_each_model_and_walls(uint32_t side, uint64_t seed, Body body) {
  for (const bool walls : {false, true})
    for (SphPressureModel model : {SphPressureModel::wcsph, SphPressureModel::thesis}) {
      const std::string name = to_string(model);
      CAPTURE(name);
      CAPTURE(walls);
      SphCase c = make_sph_case(side, model, seed);
      with_walls(c, walls);
      body(c);
    }
}

// The case's buffers on one backend, sorted into cell order.
using SphBuffers = SphCaseBuffers;
inline SphBuffers upload_sph_case(Backend& b, const SphCase& c) {
  return masav::upload_sph_case(b, c.params, c.positions, c.velocities, "test sph");
}

// The set bits of sorted particle i's 9 neighbour row masks in `rows` (n particles): its
// neighbours within h, itself included.
inline uint32_t row_mask_bits(const std::vector<uint32_t>& rows, uint32_t i, uint32_t n) {
  uint32_t bits = 0;
  for (uint32_t r = 0; r < 9; ++r)
    bits += uint32_t(std::popcount(sph::load_row_mask(sph::row_masks(rows.data(), i, n), r)));
  return bits;
}

}  // namespace masav::test
