// DFSPH kernels (dfsph_factor, dfsph_rate, dfsph_correct), one test body each, on every backend,
// against brute-force sums in double over every pair and wall image (the cross-check in
// engine/sph/dfsph_cross_checks.cpp compares the backends with the CPU reference):
//  - the factor is 1 / (|sum grad|^2 + sum |grad|^2);
//  - the density solve's prediction rho + dt drho/dt is the density the particles reach after
//    moving dt with their velocities (the spiky density and its gradient are one kernel, and a
//    wall image moves with the mirrored velocity);
//  - a correction conserves momentum (pair terms antisymmetric) and iterating the pair of
//    kernels shrinks the residual.
#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include "engine/core/error.h"
#include "engine/kernels/dfsph_params.h"
#include "engine/sph/dfsph_case_buffers.h"
#include "engine/sph/sph_kernel_calls.h"
#include "engine/sph/sph_particles.h"
#include "tests/backend_fixture.h"
#include "tests/same_bits.h"
#include "tests/sph_fixture.h"

using namespace masav;

namespace {

// A dfsph case: the jittered lattice with random velocities, spiky lattice mass, walls on.
test::SphCase dfsph_case(uint32_t side, uint64_t seed, bool walls) {
  test::SphCase c = test::make_sph_case(side, SphPressureModel::dfsph, seed);
  c.params.mass = lattice_mass(1000.0, c.dx, c.params.h, true);
  test::with_walls(c, walls);
  return c;
}

struct DfsphBuffers {
  test::SphBuffers s;
  DfsphCaseBuffers k;
  DfsphIO io() { return dfsph_io(s, k); }
};

DfsphBuffers upload(Backend& b, const test::SphCase& c) {
  DfsphBuffers d{test::upload_sph_case(b, c), make_dfsph_buffers(b, c.params.n, "test dfsph")};
  sph_density(b, c.params, {&d.s.sorted_pos, d.s.view(), &d.s.density, &d.s.pressure, &d.s.stats});
  dfsph_factor(b, DfsphParams{c.params}, d.io());
  return d;
}

// Brute force over every particle j and each of its mirror images within h of particle i
// (the nearer wall of each axis, when within h of i): f(image offset d = x_i - image, image
// velocity sign per axis, j).
struct Box {
  double lo[3], hi[3];
  bool walls;
};
template <class F>
void each_pair(const std::vector<Vec4d>& x, size_t i, const Box& box, double h, F&& f) {
  const double xi[3] = {x[i].x, x[i].y, x[i].z};
  double plane[3];
  bool near[3];
  for (int a = 0; a < 3; ++a) {
    const bool low = xi[a] - box.lo[a] <= box.hi[a] - xi[a];
    plane[a] = low ? box.lo[a] : box.hi[a];
    near[a] = box.walls && std::abs(xi[a] - plane[a]) < h;
  }
  for (size_t j = 0; j < x.size(); ++j) {
    const double xj[3] = {x[j].x, x[j].y, x[j].z};
    for (int mirror = 0; mirror < 8; ++mirror) {
      double d[3], r2 = 0;
      bool usable = true;
      for (int a = 0; a < 3; ++a) {
        const bool flip = mirror >> a & 1;
        usable = usable && (!flip || near[a]);
        d[a] = xi[a] - (flip ? 2.0 * plane[a] - xj[a] : xj[a]);
        r2 += d[a] * d[a];
      }
      if (usable && r2 < h * h && (j != i || mirror != 0)) f(d, r2, mirror, j);
    }
  }
}

Box box_of(const SphStepParams& p) {
  return {
      {p.box_min.x, p.box_min.y, p.box_min.z}, {p.box_max.x, p.box_max.y, p.box_max.z}, p.walls};
}

// m grad W_spiky for offset d.
void gradient(const double d[3], double r2, double h, double mass, double g[3]) {
  const double r = std::sqrt(r2), u = 1.0 - r / h;
  const double s = -mass * 45.0 / (M_PI * std::pow(h, 4)) * u * u / r;
  for (int a = 0; a < 3; ++a) g[a] = s * d[a];
}

// The spiky density at every particle of x (itself and its images included).
std::vector<double> spiky_density(const std::vector<Vec4d>& x, const SphStepParams& p) {
  std::vector<double> rho(x.size());
  const double w0 = p.mass * 15.0 / (M_PI * p.h * p.h * p.h);
  for (size_t i = 0; i < x.size(); ++i) {
    double sum = 1.0;  // itself
    each_pair(x, i, box_of(p), p.h, [&](const double*, double r2, int, size_t) {
      sum += std::pow(1.0 - std::sqrt(r2) / p.h, 3);
    });
    rho[i] = w0 * sum;
  }
  return rho;
}

}  // namespace

TEST_CASE("dfsph_factor equals a brute-force sum over neighbours and wall images") {
  // 1 / (|sum grad|^2 + sum |grad|^2) over neighbours and their images, the particle's own
  // images twice in the first sum and not in the second (engine/kernels/dfsph_kernels.h).
  Backend& b = test::backend();
  for (const bool walls : {false, true}) {
    CAPTURE(walls);
    const test::SphCase c = dfsph_case(11, 3, walls);
    DfsphBuffers d = upload(b, c);
    const auto x = b.download(d.s.sorted_pos);
    const auto f = b.download(d.k.factor);
    double worst = 0;
    for (size_t i = 0; i < x.size(); i += 5) {
      double sum[3] = {0, 0, 0}, sum2 = 0;
      each_pair(x, i, box_of(c.params), c.params.h,
                [&](const double* dd, double r2, int, size_t j) {
                  if (!(r2 > 0)) return;
                  double g[3];
                  gradient(dd, r2, c.params.h, c.params.mass, g);
                  const bool own = j == i;  // its own image: twice in the sum, no square
                  for (int a = 0; a < 3; ++a) sum[a] += (own ? 2.0 : 1.0) * g[a];
                  if (!own) sum2 += g[0] * g[0] + g[1] * g[1] + g[2] * g[2];
                });
      const double want = 1.0 / (sum[0] * sum[0] + sum[1] * sum[1] + sum[2] * sum[2] + sum2);
      worst = std::max(worst, std::abs(f[i] - want) / want);
    }
    INFO("worst relative difference " << worst);
    CHECK(worst < (test::sph_in_fp32(b) ? 1e-4 : 1e-12));
  }
}

TEST_CASE("dfsph_rate's density prediction is the density the particles reach") {
  Backend& b = test::backend();
  for (const bool walls : {false, true}) {
    CAPTURE(walls);
    const test::SphCase c = dfsph_case(10, 5, walls);
    DfsphBuffers d = upload(b, c);
    const double dt = 2.5e-5;  // 0.3 m/s moves a particle 7.5e-4 of the spacing
    DfsphParams p{c.params, DfsphSolve::density, dt};
    dfsph_rate(b, p, d.io());
    const auto x = b.download(d.s.sorted_pos), v = b.download(d.s.sorted_vel);
    const auto kappa = b.download(d.k.kappa), f = b.download(d.k.factor);
    // Where the particles (and with them their images) are after dt.
    std::vector<Vec4d> moved = x;
    for (size_t i = 0; i < x.size(); ++i)
      moved[i] = {x[i].x + dt * v[i].x, x[i].y + dt * v[i].y, x[i].z + dt * v[i].z, x[i].w};
    const auto before = spiky_density(x, c.params), after = spiky_density(moved, c.params);
    double change2 = 0, err2 = 0, worst = 0;
    size_t compressed = 0;
    for (size_t i = 0; i < x.size(); ++i) {
      if (!(kappa[i] > 0) || !(f[i] > 0)) continue;  // the prediction is clamped at rho0
      const double predicted = c.params.rest_density + kappa[i] * dt * dt / f[i];
      change2 += (after[i] - before[i]) * (after[i] - before[i]);
      err2 += (predicted - after[i]) * (predicted - after[i]);
      worst = std::max(worst, std::abs(predicted - after[i]));
      ++compressed;
    }
    const double rms_change = std::sqrt(change2 / double(compressed));
    INFO(compressed << " compressed particles, RMS density change " << rms_change
                    << " kg/m^3, RMS prediction error " << std::sqrt(err2 / double(compressed))
                    << ", worst " << worst);
    CHECK(compressed > x.size() / 10);
    CHECK(rms_change > 0.1);  // the velocities do move the density
    // First order in dt: the error is second order (measured 1.5e-3 of the change at this dt,
    // 6e-3 at 4 dt, on every backend) plus fp32 rounding.
    CHECK(std::sqrt(err2 / double(compressed)) < 0.01 * rms_change);
    CHECK(worst < 0.05 * rms_change + 0.01);
  }
}

TEST_CASE("dfsph_correct conserves momentum; iterating the solve shrinks the residual") {
  Backend& b = test::backend();
  // No walls, every particle free: each pair term is antisymmetric, so sum dv = 0.
  test::SphCase c = dfsph_case(10, 7, false);
  for (auto& x : c.positions) x.w = 1.0f;
  DfsphBuffers d = upload(b, c);
  const auto v0 = b.download(d.s.sorted_vel);
  std::vector<double> kappa(c.params.n);
  for (size_t i = 0; i < kappa.size(); ++i) kappa[i] = 1e-4 * (1.0 + std::sin(0.37 * double(i)));
  b.upload(d.k.kappa, kappa);
  dfsph_correct(b, DfsphParams{c.params, DfsphSolve::density, 1e-3}, d.io());
  const auto v1 = b.download(d.s.sorted_vel);
  double sum[3] = {0, 0, 0}, scale = 0;
  for (size_t i = 0; i < v1.size(); ++i) {
    const double dv[3] = {v1[i].x - v0[i].x, v1[i].y - v0[i].y, v1[i].z - v0[i].z};
    for (int a = 0; a < 3; ++a) sum[a] += dv[a];
    scale += std::sqrt(dv[0] * dv[0] + dv[1] * dv[1] + dv[2] * dv[2]);
  }
  INFO("sum dv (" << sum[0] << ", " << sum[1] << ", " << sum[2] << ") of sum |dv| " << scale);
  CHECK(scale > 0);
  for (double s : sum) CHECK(std::abs(s) < (test::sph_in_fp32(b) ? 1e-5 : 1e-12) * scale);

  // The density solve from rest on a lattice compressed by 2%, walls on: ten iterations of
  // dfsph_rate and dfsph_correct bring the mean residual down at least 5x.
  test::SphCase packed = dfsph_case(10, 9, true);
  for (auto& x : packed.positions)
    x = {0.05f + (x.x - 0.05f) * 0.98f, 0.05f + (x.y - 0.05f) * 0.98f,
         0.05f + (x.z - 0.05f) * 0.98f, x.w};
  for (auto& v : packed.velocities) v = {0, 0, 0, 0};
  test::with_walls(packed, true);
  DfsphBuffers e = upload(b, packed);
  std::vector<double> residual;
  for (uint32_t k = 0; k < 10; ++k) {
    DfsphParams p{packed.params, DfsphSolve::density, 2e-3, k, k == 0};
    dfsph_rate(b, p, e.io());
    p.first = false;
    dfsph_correct(b, p, e.io());
    const auto w = b.download(e.k.residual);
    residual.push_back(double(uint64_t(w[2 * k + 1]) << 32 | w[2 * k]));
  }
  INFO("residual units per iteration: " << residual.front() << " ... " << residual.back());
  CHECK(residual.front() > 0);
  CHECK(residual.back() < 0.2 * residual.front());
  const auto words = b.download(e.s.stats);
  CHECK(words[kSphStatNonFinite] == 0);
  CHECK(words[kSphStatOverflow] == 0);
}

TEST_CASE("dfsph_rate and dfsph_correct do nothing once the iteration before converged") {
  Backend& b = test::backend();
  test::SphCase packed = dfsph_case(8, 11, true);
  for (auto& x : packed.positions)
    x = {0.05f + (x.x - 0.05f) * 0.98f, 0.05f + (x.y - 0.05f) * 0.98f,
         0.05f + (x.z - 0.05f) * 0.98f, x.w};
  // Residual slot 3 holds 2^32 + 1000 units; each call tests it against stop_units.
  auto run = [&](uint32_t stop_slot, uint64_t stop_units) {
    DfsphBuffers e = upload(b, packed);
    std::vector<uint32_t> words(kDfsphResidualWords, 0u);
    words[6] = 1000u;
    words[7] = 1u;
    b.upload(e.k.residual, words);
    DfsphParams p{packed.params, DfsphSolve::density, 2e-3, 5, false};
    p.stop_slot = stop_slot;
    p.stop_units = stop_units;
    dfsph_rate(b, p, e.io());
    dfsph_correct(b, p, e.io());
    struct Out {
      std::vector<double> kappa, kappa_sum;
      std::vector<Vec4d> vel;
      std::vector<uint32_t> residual;
    };
    return Out{b.download(e.k.kappa), b.download(e.k.kappa_sum), b.download(e.s.sorted_vel),
               b.download(e.k.residual)};
  };
  const auto untouched = [&] {
    DfsphBuffers e = upload(b, packed);
    return std::pair{b.download(e.s.sorted_vel), b.download(e.k.kappa_sum)};
  }();
  const auto ran = run(kDfsphNoStop, 0);
  REQUIRE(!test::same_bits(ran.vel, untouched.first));  // the iteration changes the velocities
  REQUIRE(ran.residual[10] + ran.residual[11] > 0u);
  const uint64_t at = (uint64_t(1) << 32) + 1000u;
  // At or above the slot's sum: the iteration before converged, nothing runs.
  for (const uint64_t units : {at, at + 1, uint64_t(2) << 32}) {
    CAPTURE(units);
    const auto o = run(3, units);
    CHECK(test::same_bits(o.vel, untouched.first));
    CHECK(test::same_bits(o.kappa_sum, untouched.second));
    CHECK(o.residual[10] == 0u);
    CHECK(o.residual[11] == 0u);
  }
  // Below it (in the low word, or in the high word with a larger low word): both run, with the
  // bits of a call that never stops.
  for (const uint64_t units : {at - 1, uint64_t(0xffffffffu), uint64_t(0)}) {
    CAPTURE(units);
    const auto o = run(3, units);
    CHECK(test::same_bits(o.vel, ran.vel));
    CHECK(test::same_bits(o.kappa, ran.kappa));
    CHECK(test::same_bits(o.kappa_sum, ran.kappa_sum));
    CHECK(o.residual == ran.residual);
  }
}

TEST_CASE("the DFSPH kernels refuse a stop slot they cannot read") {
  Backend& b = test::backend();
  test::SphCase c = dfsph_case(6, 13, true);
  DfsphBuffers e = upload(b, c);
  DfsphParams p{c.params, DfsphSolve::density, 2e-3, 4, false};
  p.stop_slot = 4;  // the slot the rate adds to
  CHECK_THROWS_WITH_AS(dfsph_rate(b, p, e.io()), doctest::Contains("stop_slot"), Error);
  p.stop_slot = kDfsphMaxSlots;
  CHECK_THROWS_WITH_AS(dfsph_rate(b, p, e.io()), doctest::Contains("stop_slot"), Error);
  CHECK_THROWS_WITH_AS(dfsph_correct(b, p, e.io()), doctest::Contains("stop_slot"), Error);
  p.stop_slot = 3;
  DfsphIO io = e.io();
  io.residual = nullptr;
  CHECK_THROWS_WITH_AS(dfsph_correct(b, p, io), doctest::Contains("residual"), Error);
  CHECK_THROWS_WITH_AS(dfsph_factor(b, p, e.io()), doctest::Contains("stop_slot"), Error);
}
