// Host-side physics of the electron cloud (no backend): the wave functions against the thesis's
// Table 2.2 and textbook closed forms, normalisation of every state with n <= 6, expectation
// values and radial nodes, the sampling tables, Henyey-Greenstein and the direction update.
#include <doctest/doctest.h>

#include <cmath>
#include <complex>

#include "engine/atom/orbital.h"
#include "engine/atom/orbital_tables.h"
#include "engine/atom/quadrature.h"
#include "engine/kernels/scatter_math.h"
#include "engine/core/error.h"

using namespace masav;
using namespace masav::atom;

namespace {
constexpr double kPi = 3.14159265358979323846;

double radial_integral(int n, int l, int power) {
  const double end = 8.0 * n * n + 60.0;
  return integrate([&](double r) {
    const double R = radial_R(n, l, r);
    return std::pow(r, 2 + power) * R * R;
  }, 0.0, end, 4000);
}

double angular_integral(const OrbitalState& s) {
  // |Y|^2 over the sphere: Gauss-Legendre in cos theta times a 256-point rule in phi (exact for
  // trigonometric polynomials of degree < 256).
  double sum = 0;
  for (int k = 0; k < 256; ++k) {
    const double phi = 2.0 * kPi * (k + 0.5) / 256;
    sum += integrate([&](double x) { return angular_density(s, x, phi); }, -1.0, 1.0, 32);
  }
  return sum * 2.0 * kPi / 256;
}
}  // namespace

TEST_CASE("psi is normalised for every state with n <= 6, complex and real (to 1e-10)") {
  int states = 0;
  for (int n = 1; n <= 6; ++n)
    for (int l = 0; l < n; ++l) {
      const double radial = radial_integral(n, l, 0);
      CHECK(std::abs(radial - 1.0) < 1e-10);
      for (int m = -l; m <= l; ++m)
        for (bool real : {false, true}) {
          CAPTURE(n);
          CAPTURE(l);
          CAPTURE(m);
          CAPTURE(real);
          CHECK(std::abs(radial * angular_integral({n, l, m, real}) - 1.0) < 1e-10);
          ++states;
        }
    }
  CHECK(states == 2 * 91);
  // The recurrences stay accurate up to kMaxN.
  CHECK(std::abs(radial_integral(16, 3, 0) - 1.0) < 1e-9);
  CHECK(std::abs(radial_integral(16, 15, 0) - 1.0) < 1e-9);
}

TEST_CASE("|psi|^2 equals the closed forms of thesis Table 2.2 (alpha_n = 1/n)") {
  using C = std::complex<double>;
  struct Row {
    int n, l, m;
    C (*psi)(double r, double t, double p);
  };
  const double a2 = 0.5, a3 = 1.0 / 3.0;
  static const double s2 = a2, s3 = a3;
  const Row rows[] = {
      {1, 0, 0, [](double r, double, double) { return C(std::exp(-r) / std::sqrt(kPi)); }},
      {2, 0, 0, [](double r, double, double) {
         return C(std::pow(s2, 1.5) * (1 - s2 * r) * std::exp(-s2 * r) / std::sqrt(kPi));
       }},
      {2, 1, 0, [](double r, double t, double) {
         return C(std::pow(s2, 2.5) * r * std::exp(-s2 * r) * std::cos(t) / std::sqrt(kPi));
       }},
      {2, 1, 1, [](double r, double t, double p) {
         return std::pow(s2, 2.5) * r * std::exp(-s2 * r) * std::sin(t) *
                std::exp(C(0, p)) / std::sqrt(2 * kPi);
       }},
      {3, 0, 0, [](double r, double, double) {
         return C(std::pow(s3, 1.5) * (3 - 6 * s3 * r + 2 * s3 * s3 * r * r) * std::exp(-s3 * r) /
                  (3 * std::sqrt(kPi)));
       }},
      // Textbook normalisation for (3,1,0): sqrt(2)/(81 sqrt(pi)) (6 - r) r e^{-r/3} cos t.
      {3, 1, 0, [](double r, double t, double) {
         return C(std::sqrt(2.0) / (81 * std::sqrt(kPi)) * (6 - r) * r * std::exp(-r / 3) *
                  std::cos(t));
       }},
      {3, 2, 0, [](double r, double t, double) {
         return C(std::pow(s3, 3.5) * r * r * std::exp(-s3 * r) *
                  (3 * std::cos(t) * std::cos(t) - 1) / (3 * std::sqrt(2 * kPi)));
       }},
      {3, 2, 2, [](double r, double t, double p) {
         return std::pow(s3, 3.5) * r * r * std::exp(-s3 * r) * std::sin(t) * std::sin(t) *
                std::exp(C(0, 2 * p)) / (2 * std::sqrt(3 * kPi));
       }},
  };
  (void)a2;
  (void)a3;
  for (const Row& row : rows)
    for (double r : {0.3, 1.0, 2.5, 7.0, 13.0})
      for (double t : {0.2, 1.1, 2.9})
        for (double p : {0.0, 0.7, 4.0}) {
          CAPTURE(row.n);
          CAPTURE(row.l);
          CAPTURE(row.m);
          const double want = std::norm(row.psi(r, t, p));
          const double got = density({row.n, row.l, row.m, false}, r, std::cos(t), p);
          CHECK(std::abs(got - want) <= 1e-12 * std::max(want, 1e-12) + 1e-300);
        }
}

TEST_CASE("expectation values by quadrature equal the closed forms") {
  for (int n = 1; n <= 8; ++n)
    for (int l = 0; l < n; ++l) {
      CAPTURE(n);
      CAPTURE(l);
      CHECK(std::abs(radial_integral(n, l, 1) - expect_r(n, l)) < 1e-9 * expect_r(n, l));
      CHECK(std::abs(radial_integral(n, l, 2) - expect_r2(n, l)) < 1e-9 * expect_r2(n, l));
      CHECK(std::abs(radial_integral(n, l, -1) - expect_inv_r(n)) < 1e-9);
      for (int m = 0; m <= l; ++m) {
        const double c2 = integrate([&](double x) {
          return x * x * angular_density({n, l, m, false}, x, 0.0) * 2 * kPi;
        }, -1, 1, 32);
        CHECK(std::abs(c2 - expect_cos2(l, m)) < 1e-12);
      }
    }
}

TEST_CASE("radial nodes: roots of the Laguerre polynomial equal the closed forms") {
  CHECK(radial_nodes(1, 0).empty());
  CHECK(radial_nodes(3, 2).empty());
  auto near = [](const std::vector<double>& got, std::vector<double> want) {
    REQUIRE(got.size() == want.size());
    for (size_t i = 0; i < got.size(); ++i) CHECK(std::abs(got[i] - want[i]) < 1e-9);
  };
  near(radial_nodes(2, 0), {2.0});
  near(radial_nodes(3, 0), {(9 - 3 * std::sqrt(3.0)) / 2, (9 + 3 * std::sqrt(3.0)) / 2});
  near(radial_nodes(3, 1), {6.0});
  near(radial_nodes(4, 1), {10 - 2 * std::sqrt(5.0), 10 + 2 * std::sqrt(5.0)});
  near(radial_nodes(4, 2), {12.0});
  for (double r : radial_nodes(6, 1)) CHECK(std::abs(radial_R(6, 1, r)) < 1e-10);
}

TEST_CASE("presets are thesis Table 2.1; bad states name the field and the range") {
  const OrbitalState s8 = preset_state("state8");
  CHECK(s8.n == 3);
  CHECK(s8.l == 2);
  CHECK(s8.m == 0);
  CHECK(preset_state("state4").m == 1);
  CHECK(preset_names().size() == 10);
  CHECK_THROWS_WITH_AS(preset_state("state11"), doctest::Contains("state1 .. state10"), Error);
  CHECK_THROWS_WITH_AS(validate_state({2, 2, 0}), doctest::Contains("invalid l = 2"), Error);
  CHECK_THROWS_WITH_AS(validate_state({3, 1, -2}), doctest::Contains("invalid m = -2"), Error);
  CHECK_THROWS_WITH_AS(validate_state({17, 0, 0}), doctest::Contains("invalid n = 17"), Error);
  CHECK_THROWS_WITH_AS(validate_state({0, 0, 0}), doctest::Contains("[1, 16]"), Error);
}

TEST_CASE("sampling tables: exact bin masses, 99.9 % box, truncated tail") {
  const OrbitalState s{3, 1, -1, true};
  const OrbitalTables t = make_orbital_tables(s, OrbitalPlacement::exact, 10, 1);
  CHECK(t.params.azimuth_bins == 1024);
  CHECK(t.params.azimuth_periods == 2);
  CHECK(t.params.azimuth_offset == doctest::Approx(kPi / 2));
  CHECK(t.truncated_mass < 1e-11);
  const uint32_t kr = t.params.radial_bins;
  REQUIRE(t.cdf.size() == size_t(kr + 1 + t.params.polar_bins + 1 + 1024 + 1));
  CHECK(t.cdf[0] == 0);
  CHECK(t.cdf[kr] == kCdfOne);
  for (uint32_t k : {100u, 700u, 2000u}) {
    const double a = t.params.radial_max_a0 * k / kr;
    const double want = radial_probability(s, 0, a) / radial_probability(s, 0, t.params.radial_max_a0);
    CHECK(std::abs(t.cdf[k] / double(kCdfOne) - want) < 1.0 / kCdfOne);
  }
  for (int state = 1; state <= 10; ++state) {
    const OrbitalState p = preset_state("state" + std::to_string(state));
    const double L = box_half_width(p, 0.999);
    CHECK(radial_probability(p, 0, L) == doctest::Approx(0.999).epsilon(1e-9));
  }
  // Shell placement places exactly `count` particles.
  const OrbitalTables sh = make_orbital_tables(s, OrbitalPlacement::shells, 12345, 1);
  CHECK(sh.cdf.back() == 12345u);
  TableOptions bad;
  bad.radial_bins = 3;
  CHECK_THROWS_WITH_AS(make_orbital_tables(s, OrbitalPlacement::exact, 1, 1, bad),
                       doctest::Contains("radial_bins"), Error);
}

TEST_CASE("Henyey-Greenstein sampling has mean cos theta = g; the direction update keeps |d| = 1") {
  for (double g : {-0.5, 0.0, 0.3, 0.6, 0.9}) {
    const int n = 200000;
    double mean = 0;
    for (int i = 0; i < n; ++i) mean += scatter::hg_cos_theta(g, (i + 0.5) / n);
    CHECK(mean / n == doctest::Approx(g).epsilon(1e-3));
  }
  using V = hd::V3<double>;
  for (V d : {V{0, 0, 1}, V{0, 0, -1}, hd::normalize(V{1, 2, 3}), hd::normalize(V{-3, 0.5, -0.2})})
    for (double ct : {-0.9, 0.0, 0.4, 0.99})
      for (double phi : {0.1, 2.0, 5.5}) {
        const V n = scatter::scatter_direction(d, ct, phi);
        CHECK(std::abs(hd::length(n) - 1) < 1e-12);
        CHECK(std::abs(hd::dot(n, d) - ct) < 1e-12);
      }
  // The thesis's printed formula (d'_y with "- d_x sin phi") leaves the unit sphere.
  const V d = hd::normalize(V{1, 2, 3});
  const double ct = 0.4, st = std::sqrt(1 - ct * ct), phi = 2.0, zeta = std::sqrt(1 - d.z * d.z);
  const V thesis{st / zeta * (d.x * d.z * std::cos(phi) - d.y * std::sin(phi)) + d.x * ct,
                 st / zeta * (d.y * d.z * std::cos(phi) - d.x * std::sin(phi)) + d.y * ct,
                 -zeta * st * std::cos(phi) + d.z * ct};
  CHECK(std::abs(hd::length(thesis) - 1) > 1e-3);
}
