#include "engine/sph/sph_particles.h"

#include <fmt/format.h>

#include <cmath>
#include <numbers>

#include "engine/core/error.h"
#include "engine/kernels/philox.h"
#include "engine/kernels/sph_kernels.h"

namespace masav {

double lattice_mass(double rho0, double dx, double h, bool spiky) {
  const int reach = int(std::ceil(h / dx));
  double sum = 0;
  for (int i = -reach; i <= reach; ++i)
    for (int j = -reach; j <= reach; ++j)
      for (int k = -reach; k <= reach; ++k) {
        const double r2 = (double(i) * i + double(j) * j + double(k) * k) * dx * dx;
        if (r2 < h * h) {
          const double u = spiky ? 1.0 - std::sqrt(r2) / h : 1.0 - r2 / (h * h);
          sum += u * u * u;
        }
      }
  const double w0 =
      spiky ? 15.0 / (std::numbers::pi * h * h * h) : 315.0 / (64.0 * std::numbers::pi * h * h * h);
  return rho0 / (w0 * sum);
}

double spiky_gradient_moment(double dx, double h, bool spiky) {
  const int reach = int(std::ceil(h / dx));
  double density = 0, moment = 0;  // per unit mass
  for (int i = -reach; i <= reach; ++i)
    for (int j = -reach; j <= reach; ++j)
      for (int k = -reach; k <= reach; ++k) {
        const double r = std::sqrt(double(i) * i + double(j) * j + double(k) * k) * dx;
        if (r >= h) continue;
        const double u = spiky ? 1.0 - r / h : 1.0 - (r * r) / (h * h);
        density += (spiky ? 15.0 / (std::numbers::pi * h * h * h)
                          : 315.0 / (64.0 * std::numbers::pi * h * h * h)) *
                   u * u * u;
        moment += r * 45.0 / (std::numbers::pi * std::pow(h, 6)) * (h - r) * (h - r) / 3.0;
      }
  return moment / density;  // m / rho0 = 1 / density for the lattice-normalised mass
}

namespace {

// Every particle inside the fluid has about 4/3 pi (h/dx)^3 neighbours, each one a candidate of
// the neighbour walk, and the lattice sums below loop over (2 h/dx + 3)^3 points: h is bounded
// by max_candidates before any of it runs, and the message names the largest legal value.
void check_support(const SphScene& s, double dx, double h) {
  const double most = std::cbrt(3.0 * s.max_candidates / (4.0 * std::numbers::pi));
  if (h <= most * dx) return;
  const std::string why = fmt::format(
      "a particle would have about {:.3g} neighbours, over max_candidates = {} (the particle "
      "spacing dx is {:.4g} m)",
      4.0 / 3.0 * std::numbers::pi * std::pow(h / dx, 3), s.max_candidates, dx);
  if (s.smoothing_radius)
    throw_invalid("sph scene", "smoothing_radius", fmt::format("{}", h),
                  fmt::format("at most {:.4g} m ({:.3g} dx): {}", most * dx, most, why));
  throw_invalid("sph scene", "h_over_dx", fmt::format("{}", s.h_over_dx),
                fmt::format("at most {:.3g} here: {}", most, why));
}

}  // namespace

SphSpacing sph_spacing(const SphScene& s) {
  validate(s);
  SphSpacing out;
  const Vec3d lo = s.block.min, hi = s.block.max;
  const double ext[3] = {hi.x - lo.x, hi.y - lo.y, hi.z - lo.z};
  const double n = double(s.particles);
  const double sp = std::cbrt(ext[0] * ext[1] * ext[2] / n);
  // Whole columns that fit in x and z (never wider than the block); the layers in y take the
  // rest, the top one possibly partial.
  const uint32_t nx = std::max(1u, uint32_t(std::floor(ext[0] / sp + 1e-6)));
  const uint32_t nz = std::max(1u, uint32_t(std::floor(ext[2] / sp + 1e-6)));
  const uint32_t ny =
      uint32_t((uint64_t(s.particles) + uint64_t(nx) * nz - 1) / (uint64_t(nx) * nz));
  out.lattice = {nx, ny, nz};
  out.placed_dx = sp;
  out.dx = sp * std::cbrt(s.block.density_ratio);
  out.h = s.smoothing_radius ? *s.smoothing_radius : s.h_over_dx * out.dx;
  check_support(s, out.dx, out.h);
  out.fluid = s.particles;
  if (s.obstacle.enabled) {
    const Vec3d a = s.obstacle.min, b = s.obstacle.max;
    const auto count = [&](double len) { return std::max(1u, uint32_t(std::floor(len / out.dx))); };
    const uint32_t ox = count(b.x - a.x), oy = count(b.y - a.y), oz = count(b.z - a.z);
    if (uint64_t(ox) * oy * oz + s.particles > UINT32_MAX)
      throw_invalid("sph scene", "obstacle", fmt::format("{} x {} x {} particles", ox, oy, oz),
                    "fewer than 2^32 particles in all");
    out.obstacle = {ox, oy, oz};
  }
  return out;
}

SphParticles build_particles(const SphScene& s) {
  const SphSpacing spacing = sph_spacing(s);
  SphParticles out;
  const Vec3d lo = s.block.min;
  const double sp = spacing.placed_dx;
  const uint32_t nx = spacing.lattice.x, ny = spacing.lattice.y, nz = spacing.lattice.z;
  out.lattice = spacing.lattice;
  out.placed_dx = sp;
  out.dx = spacing.dx;
  out.h = spacing.h;
  out.mass = lattice_mass(s.rest_density, out.dx, out.h, s.model != SphPressureModel::thesis);
  out.gradient_correction =
      1.0 / spiky_gradient_moment(out.dx, out.h, s.model != SphPressureModel::thesis);

  // Layer heights: uniform, or (hydrostatic) each layer's spacing shrunk by the Tait density
  // under the weight of the layers above it (spacing ~ 1 / density in a box whose walls hold the
  // fluid laterally).
  std::vector<double> layer_y(ny);
  const double g = -s.gravity.y;
  if (s.block.hydrostatic && s.model == SphPressureModel::wcsph && g > 0) {
    const double b = s.rest_density * s.sound_speed * s.sound_speed / 7.0;
    double depth = 0.0;  // below the top particle's upper face
    std::vector<double> dy(ny);
    for (uint32_t k = ny; k-- > 0;) {
      const double rho =
          s.rest_density * std::pow(1.0 + s.rest_density * g * (depth + 0.5 * sp) / b, 1.0 / 7.0);
      dy[k] = sp * s.rest_density / rho;
      depth += dy[k];
    }
    double y = lo.y;
    for (uint32_t k = 0; k < ny; ++k) {
      layer_y[k] = y + 0.5 * dy[k];
      y += dy[k];
    }
  } else {
    for (uint32_t k = 0; k < ny; ++k) layer_y[k] = lo.y + (k + 0.5) * sp;
  }

  const uint64_t key = s.seed;
  out.positions.reserve(s.particles);
  for (uint32_t i = 0; i < s.particles; ++i) {
    const uint32_t layer = i / (nx * nz), rem = i % (nx * nz);
    const uint32_t iz = rem / nx, ix = rem % nx;
    Vec4d p{lo.x + (ix + 0.5) * sp, layer_y[layer], lo.z + (iz + 0.5) * sp, 1.0};
    if (s.jitter > 0) {
      const philox::Block r = philox::stream_block(key, 1, i);
      p.x += (2.0 * philox::u01(r.w[0]) - 1.0) * s.jitter * sp;
      p.y += (2.0 * philox::u01(r.w[1]) - 1.0) * s.jitter * sp;
      p.z += (2.0 * philox::u01(r.w[2]) - 1.0) * s.jitter * sp;
    }
    if (p.x < s.box_min.x || p.y < s.box_min.y || p.z < s.box_min.z || p.x > s.box_max.x ||
        p.y > s.box_max.y || p.z > s.box_max.z)
      throw_invalid("sph scene", "box",
                    fmt::format("({}, {}, {}) .. ({}, {}, {})", s.box_min.x, s.box_min.y,
                                s.box_min.z, s.box_max.x, s.box_max.y, s.box_max.z),
                    fmt::format("large enough for the fluid's {} x {} x {} lattice at spacing {} m "
                                "(particle {} falls outside); grow the box or lower particles",
                                nx, ny, nz, sp, i));
    out.positions.push_back(p);
    out.velocities.push_back({s.block.velocity.x, s.block.velocity.y, s.block.velocity.z, 0.0});
  }
  out.fluid = s.particles;

  if (s.obstacle.enabled) {
    const double inv_mass = s.obstacle.pinned ? 0.0 : 1.0 / s.obstacle.mass_ratio;
    const Vec3d a = s.obstacle.min;
    const uint32_t ox = spacing.obstacle.x, oy = spacing.obstacle.y, oz = spacing.obstacle.z;
    for (uint32_t iy = 0; iy < oy; ++iy)
      for (uint32_t iz = 0; iz < oz; ++iz)
        for (uint32_t ix = 0; ix < ox; ++ix) {
          out.positions.push_back({a.x + (ix + 0.5) * out.dx, a.y + (iy + 0.5) * out.dx,
                                   a.z + (iz + 0.5) * out.dx, inv_mass});
          out.velocities.push_back({0, 0, 0, 0});
        }
    out.obstacle = ox * oy * oz;
  }
  return out;
}

}  // namespace masav
