// Cloud density and nebula lighting on every backend: the density grid against a brute-force
// count; Eq. 2.4 against its closed form in a uniform medium; the midpoint path's error falling
// with the step against the exact voxel traversal; light linear in Phi; Eq. 2.5-2.6 against a
// synthetic table; the CPU reference on a real cloud; bad input.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "engine/atom/orbital_tables.h"
#include "engine/atom/scatter_cache.h"
#include "engine/core/error.h"
#include "engine/grid/hash_grid.h"
#include "engine/kernels/grid_cell.h"
#include "engine/kernels/volume_math.h"
#include "engine/util/error_metrics.h"
#include "tests/backend_fixture.h"

using namespace masav;

namespace {

constexpr double kPi = 3.14159265358979323846;

std::vector<Vec4f> random_points(size_t n, float lo, float hi, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<float> u(lo, hi);
  std::vector<Vec4f> p(n);
  for (auto& v : p) v = {u(rng), u(rng), u(rng), 0.0f};
  return p;
}

NebulaLightParams uniform_setup(uint32_t n) {
  NebulaLightParams p;
  p.grid = make_grid_params({-5, -5, -5}, 0.5f, {20, 20, 20}, n);
  p.kappa_a2 = 2.0f;
  p.albedo = 0.5f;
  p.core_radius_a0 = 1e-3f;
  p.source_power_lm = 1000.0f;
  return p;
}

// Length of the segment a -> b inside the box [lo, hi]^3.
double inside_length(hd::V3<double> a, hd::V3<double> b, double lo, double hi) {
  const hd::V3<double> d = b - a;
  const double len = hd::length(d);
  double t0 = 0, t1 = len;
  if (!volume::slab(a, d * (1 / len), hd::V3<double>{lo, lo, lo}, hd::V3<double>{hi, hi, hi}, t0,
                    t1))
    return 0;
  return t1 - t0;
}

std::vector<double> illuminate(Backend& b, const NebulaLightParams& p,
                               const std::vector<Vec4f>& pts, const std::vector<double>& dens) {
  auto pos = b.create<Real4>(pts.size(), "positions");
  b.upload(pos, pts);
  auto density = b.create<Real>(dens.size(), "density");
  b.upload(density, dens);
  auto out = b.create<Real>(pts.size(), "illumination");
  b.nebula_illuminate(p, pos, density, out);
  return b.download(out);
}

// n positions of the orbital whose tables are t, sampled on the reference.
std::vector<Vec4f> sample_cloud(Backend& r, const atom::OrbitalTables& t, uint32_t n) {
  auto tables = r.create<uint32_t>(t.cdf.size(), "tables");
  r.upload(tables, t.cdf);
  auto pos = r.create<Real4>(n, "positions");
  r.orbital_sample(t.params, tables, pos);
  return r.download_f32(pos);
}

}  // namespace

TEST_CASE("cloud_density counts the hash grid's cells (probability per a0^3)") {
  const atom::OrbitalState s{3, 1, 1, false};
  const uint32_t n = 20000;
  const auto t = atom::make_orbital_tables(s, OrbitalPlacement::exact, n, 5);
  Backend& r = test::reference();
  const std::vector<Vec4f> pts = sample_cloud(r, t, n);
  const float half = float(atom::box_half_width(s));
  const GridParams g = make_grid_params({-half, -half, -half}, 2 * half / 24, {24, 24, 24}, n);
  Backend& b = test::backend();
  auto pos = b.create<Real4>(n, "positions");
  b.upload(pos, pts);
  HashGrid grid = make_hash_grid(b, g, n);
  build_hash_grid(b, grid, pos);
  auto density = b.create<Real>(grid_cell_count(g), "density");
  b.cloud_density({g, n}, grid.cell_start, grid.cell_end, density);
  const auto got = b.download(density);
  std::vector<double> want(got.size(), 0.0);
  const float origin[3] = {g.origin.x, g.origin.y, g.origin.z};
  const uint32_t dims[3] = {24, 24, 24};
  const double cell3 = double(g.cell_size) * g.cell_size * g.cell_size;
  for (const auto& v : pts) {
    const auto c = grid::point_cell(v.x, v.y, v.z, origin, g.inv_cell, dims);
    want[grid::cell_id(c.x, c.y, c.z, 24, 24)] += 1.0 / (n * cell3);
  }
  const ErrorStats e = compare(got, want, 1e-6);
  CAPTURE(describe(e));
  CHECK(e.max_rel < 1e-6);
  double total = 0;
  for (double d : got) total += d * cell3;
  CHECK(total == doctest::Approx(1.0).epsilon(1e-5));
}

TEST_CASE("nebula_illuminate equals Phi/(4 pi r^2) exp(-tau) in a uniform medium, both paths") {
  const auto pts = random_points(3000, -6.0f, 6.0f, 3);  // some outside the grid
  NebulaLightParams p = uniform_setup(uint32_t(pts.size()));
  const std::vector<double> dens(8000, 0.2);
  const double ext = 0.2 * p.kappa_a2 / p.albedo;
  for (OpticalPath path : {OpticalPath::exact, OpticalPath::midpoint}) {
    CAPTURE(int(path));
    p.path = path;
    p.step_a0 = 0.37f;
    const auto got = illuminate(test::backend(), p, pts, dens);
    std::vector<double> want(pts.size());
    for (size_t i = 0; i < pts.size(); ++i) {
      const hd::V3<double> x{pts[i].x, pts[i].y, pts[i].z};
      const double r = std::max(hd::length(x), double(p.core_radius_a0));
      want[i] = p.source_power_lm / (4 * kPi * r * r) *
                std::exp(-ext * inside_length({0, 0, 0}, x, -5, 5));
    }
    const ErrorStats e = compare(got, want, 1e-12);
    CAPTURE(describe(e));
    CHECK(e.max_rel < 2e-5);
  }
}

TEST_CASE("optical depth: the midpoint path's error falls with the step; light is linear in Phi") {
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<double> dens(16 * 16 * 16);
  for (double& d : dens) d = u(rng);
  const auto pts = random_points(400, -3.9f, 3.9f, 8);
  NebulaLightParams p;
  p.grid = make_grid_params({-4, -4, -4}, 0.5f, {16, 16, 16}, 400);
  p.albedo = 1.0f;
  p.core_radius_a0 = 1e-3f;
  p.source_power_lm = 1.0f;
  auto tau_of = [&](const std::vector<double>& illum) {
    std::vector<double> tau(illum.size());
    for (size_t i = 0; i < illum.size(); ++i) {
      const double r = std::max(double(p.core_radius_a0), std::sqrt(double(pts[i].x) * pts[i].x +
                                                                    double(pts[i].y) * pts[i].y +
                                                                    double(pts[i].z) * pts[i].z));
      tau[i] = -std::log(illum[i] * 4 * kPi * r * r);
    }
    return tau;
  };
  p.path = OpticalPath::exact;
  const auto exact = tau_of(illuminate(test::backend(), p, pts, dens));
  p.path = OpticalPath::midpoint;
  double prev = 0;
  for (float step : {0.2f, 0.1f, 0.05f, 0.025f, 0.0125f}) {
    p.step_a0 = step;
    const auto mid = tau_of(illuminate(test::backend(), p, pts, dens));
    double err = 0, mean_tau = 0;
    for (size_t i = 0; i < mid.size(); ++i)
      err += std::abs(mid[i] - exact[i]), mean_tau += exact[i];
    err /= double(mid.size());
    mean_tau /= double(mid.size());
    MESSAGE("midpoint step " << step << " a0: mean |tau error| " << err << " (mean tau " << mean_tau
                             << ")");
    if (prev > 0) CHECK(err < 0.75 * prev);  // O(step): about halves with the step
    prev = err;
  }
  CHECK(prev < 0.4 * 0.0125);  // about 0.3 step: first order, as the grid is discontinuous
  // Linear in the source power.
  p.path = OpticalPath::exact;
  const auto one = illuminate(test::backend(), p, pts, dens);
  p.source_power_lm = 250000.0f;
  const auto many = illuminate(test::backend(), p, pts, dens);
  for (size_t i = 0; i < one.size(); ++i)
    CHECK(many[i] == doctest::Approx(250000.0 * one[i]).epsilon(1e-6));
}

TEST_CASE("nebula_view equals illumination * P(tau, cos) * exp(-tau_view) for a known table") {
  const auto pts = random_points(2000, -4.9f, 4.9f, 21);
  NebulaLightParams p = uniform_setup(uint32_t(pts.size()));
  p.viewer = {30, 10, 20};
  p.table_rows = 50;
  p.table_bins = 8;
  p.table_tau_step = 0.1f;
  const uint32_t stride = p.table_bins;
  std::vector<double> table(p.table_rows * stride, 0.0);
  auto linear = [](double tau, double mu) { return 0.01 * (1 + 0.5 * tau + 0.3 * mu); };
  for (uint32_t r = 0; r < p.table_rows; ++r)
    for (uint32_t b = 0; b < p.table_bins; ++b)
      table[r * stride + b] = linear(r * 0.1, -1 + (b + 0.5) * 2.0 / p.table_bins);
  const std::vector<double> dens(8000, 0.2), illum(pts.size(), 3.0);
  Backend& b = test::backend();
  auto pos = b.create<Real4>(pts.size(), "positions");
  b.upload(pos, pts);
  auto density = b.create<Real>(dens.size(), "density");
  b.upload(density, dens);
  auto tab = b.create<Real>(table.size(), "table");
  b.upload(tab, table);
  auto ill = b.create<Real>(pts.size(), "illumination");
  b.upload(ill, illum);
  auto light = b.create<Real>(pts.size(), "light");
  b.nebula_view(p, pos, density, tab, ill, light);
  const auto got = b.download(light);
  const double tau_sct = double(p.kappa_a2) * 0.2 * 0.5;
  const double mu_end = 1 - 1.0 / p.table_bins;
  std::vector<double> want(pts.size());
  for (size_t i = 0; i < pts.size(); ++i) {
    const hd::V3<double> x{pts[i].x, pts[i].y, pts[i].z}, v{30, 10, 20};
    const double mu = hd::dot(x, v - x) / (hd::length(x) * hd::length(v - x));
    const double per_sr =
        linear(tau_sct, std::clamp(mu, -mu_end, mu_end)) / (2 * kPi * 2.0 / p.table_bins);
    want[i] = 3.0 * per_sr * std::exp(-0.2 * p.kappa_a2 / p.albedo * inside_length(x, v, -5, 5));
  }
  const ErrorStats e = compare(got, want, 1e-12);
  CAPTURE(describe(e));
  CHECK(e.max_rel < 2e-5);
}

TEST_CASE("nebula lighting of a real cloud matches the CPU reference") {
  const atom::OrbitalState s = atom::preset_state("state3");
  const uint32_t n = 20000;
  const auto t = atom::make_orbital_tables(s, OrbitalPlacement::exact, n, 11);
  Backend& r = test::reference();
  const std::vector<Vec4f> pts = sample_cloud(r, t, n);
  ScatterTableParams sp;  // a smooth table: bilinear weights in fp32 carry ~1e-6 absolute error
  sp.rows = 100;
  sp.tau_step = 0.1f;
  sp.photons_per_row = 2048;
  const std::vector<double> table = atom::make_phase_table(atom::compute_scatter_table(r, sp));
  const float half = float(atom::box_half_width(s));
  NebulaLightParams p;
  p.grid = make_grid_params({-half, -half, -half}, 2 * half / 24, {24, 24, 24}, n);
  p.kappa_a2 = float(1.0 / (atom::peak_density(s) * p.grid.cell_size));  // tau_sct ~ 1 at the peak
  p.viewer = {0, -40, 10};
  p.table_rows = sp.rows;
  p.table_tau_step = sp.tau_step;
  auto run = [&](Backend& b) {
    auto pos = b.create<Real4>(n, "positions");
    b.upload(pos, pts);
    HashGrid grid = make_hash_grid(b, p.grid, n);
    build_hash_grid(b, grid, pos);
    auto density = b.create<Real>(grid_cell_count(p.grid), "density");
    b.cloud_density({p.grid, n}, grid.cell_start, grid.cell_end, density);
    auto tab = b.create<Real>(table.size(), "table");
    b.upload(tab, table);
    auto ill = b.create<Real>(n, "illumination"), light = b.create<Real>(n, "light");
    b.nebula_illuminate(p, pos, density, ill);
    b.nebula_view(p, pos, density, tab, ill, light);
    return std::pair{b.download(ill), b.download(light)};
  };
  const auto got = run(test::backend()), want = run(r);
  // Relative errors against 1e-6 of the largest value (light spans many decades).
  auto floor_of = [](const std::vector<double>& v) {
    return 1e-6 * *std::max_element(v.begin(), v.end());
  };
  const ErrorStats ei = compare(got.first, want.first, floor_of(want.first));
  const ErrorStats el = compare(got.second, want.second, floor_of(want.second));
  CAPTURE(describe(ei));
  CAPTURE(describe(el));
  CHECK(ei.rel_l2 < 1e-5);
  CHECK(ei.max_rel < 1e-4);
  CHECK(el.rel_l2 < 1e-5);
  CHECK(el.max_rel < 2e-3);  // fp32 interpolation weights: ~1e-6 absolute on a sparse table
}

TEST_CASE("nebula kernels reject bad input, naming the field") {
  Backend& b = test::backend();
  NebulaLightParams p = uniform_setup(10);
  auto pos = b.create<Real4>(10, "positions");
  auto density = b.create<Real>(8000, "density");
  auto out = b.create<Real>(10, "out");
  p.albedo = 0;
  CHECK_THROWS_WITH_AS(b.nebula_illuminate(p, pos, density, out), doctest::Contains("albedo"),
                       Error);
  p.albedo = 0.6f;
  p.path = OpticalPath::midpoint;
  p.step_a0 = 1e-6f;
  CHECK_THROWS_WITH_AS(b.nebula_illuminate(p, pos, density, out), doctest::Contains("step_a0"),
                       Error);
  p.path = OpticalPath::exact;
  p.viewer = {NAN, 0, 0};
  CHECK_THROWS_WITH_AS(b.nebula_illuminate(p, pos, density, out), doctest::Contains("viewer"),
                       Error);
  p.viewer = {0, 0, 10};
  auto small = b.create<Real>(100, "density");
  CHECK_THROWS_WITH_AS(b.nebula_illuminate(p, pos, small, out), doctest::Contains("density size"),
                       Error);
  auto table = b.create<Real>(10, "table");
  CHECK_THROWS_WITH_AS(b.nebula_view(p, pos, density, table, out, out),
                       doctest::Contains("table size"), Error);
}
