// orbital_sample on every backend: the same cloud as the CPU reference up to fp32 rounding;
// moments against closed-form hydrogen expectation values; radial nodes; chi-square of the
// angular distributions; the thesis's shell placement; bad input.
#include <doctest/doctest.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "engine/atom/orbital_tables.h"
#include "engine/core/error.h"
#include "tests/backend_fixture.h"

using namespace masav;
using namespace masav::atom;

namespace {

constexpr double kPi = 3.14159265358979323846;

std::vector<Vec4d> sample_on(Backend& b, const OrbitalTables& t) {
  auto tables = b.create<uint32_t>(t.cdf.size(), "orbital tables");
  b.upload(tables, t.cdf);
  auto pos = b.create<Real4>(t.params.count, "positions");
  b.orbital_sample(t.params, tables, pos);
  return b.download(pos);
}

struct Moments {
  double r = 0, r2 = 0, inv_r = 0, z2 = 0, x2 = 0, y2 = 0;
  double var_r = 0, var_r2 = 0, var_inv_r = 0, var_z2 = 0;
};

Moments moments(const std::vector<Vec4d>& p) {
  Moments m;
  double r4 = 0, ir2 = 0, z4 = 0;
  for (const auto& v : p) {
    const double rr = v.x * v.x + v.y * v.y + v.z * v.z, r = std::sqrt(rr);
    m.r += r;
    m.r2 += rr;
    m.inv_r += 1.0 / r;
    m.z2 += v.z * v.z;
    m.x2 += v.x * v.x;
    m.y2 += v.y * v.y;
    r4 += rr * rr;
    ir2 += 1.0 / rr;
    z4 += v.z * v.z * v.z * v.z;
  }
  const double n = double(p.size());
  m.r /= n, m.r2 /= n, m.inv_r /= n, m.z2 /= n, m.x2 /= n, m.y2 /= n;
  m.var_r = m.r2 - m.r * m.r;
  m.var_r2 = r4 / n - m.r2 * m.r2;
  m.var_inv_r = ir2 / n - m.inv_r * m.inv_r;
  m.var_z2 = z4 / n - m.z2 * m.z2;
  return m;
}

// |sampled - exact| within 5 standard errors of the sample mean.
void check_moment(const char* name, double got, double want, double var, size_t n) {
  CAPTURE(name);
  CAPTURE(got);
  CAPTURE(want);
  CHECK(std::abs(got - want) <= 5.0 * std::sqrt(var / double(n)) + 1e-9 * std::abs(want));
}

// Pearson chi-square of counts against expected probabilities; bins with < 5 expected pooled.
double chi_square(const std::vector<double>& counts, const std::vector<double>& prob, size_t n,
                  int& dof) {
  double chi = 0, pool_c = 0, pool_e = 0;
  dof = -1;
  for (size_t i = 0; i < counts.size(); ++i) {
    const double e = prob[i] * double(n);
    if (e < 5) {
      pool_c += counts[i];
      pool_e += e;
      continue;
    }
    chi += (counts[i] - e) * (counts[i] - e) / e;
    ++dof;
  }
  if (pool_e > 0) chi += (pool_c - pool_e) * (pool_c - pool_e) / std::max(pool_e, 1.0), ++dof;
  return chi;
}

// Chi-square quantile for p = 1e-4 (Wilson-Hilferty), a test that fails by chance 1 in 10^4.
double chi_critical(int dof) {
  const double z = 3.719, k = dof;
  const double t = 1.0 - 2.0 / (9.0 * k) + z * std::sqrt(2.0 / (9.0 * k));
  return k * t * t * t;
}

}  // namespace

TEST_CASE("orbital_sample draws the CPU reference's cloud, up to fp32 rounding") {
  const OrbitalState states[] = {{2, 1, 0, false}, {3, 2, -1, true}, {5, 3, 2, true}};
  for (const OrbitalState& s : states) {
    for (OrbitalPlacement pl : {OrbitalPlacement::exact, OrbitalPlacement::shells}) {
      CAPTURE(describe(s));
      CAPTURE(int(pl));
      const OrbitalTables t = make_orbital_tables(s, pl, 30011, 42);
      const auto got = sample_on(test::backend(), t), want = sample_on(test::reference(), t);
      REQUIRE(got.size() == want.size());
      double max_err = 0;
      for (size_t i = 0; i < got.size(); ++i)
        max_err = std::max({max_err, std::abs(got[i].x - want[i].x), std::abs(got[i].y - want[i].y),
                            std::abs(got[i].z - want[i].z)});
      // fp32 positions and sin/cos: ~1e-6 of the cloud's extent (tolerance 2e-5).
      CHECK(max_err <= 2e-5 * t.params.radial_max_a0);
    }
  }
}

TEST_CASE("sampled moments equal closed-form hydrogen expectation values (5 sigma)") {
  const OrbitalState states[] = {{1, 0, 0, false}, {2, 1, 1, false}, {3, 2, 0, false},
                                 {3, 1, -1, true}, {4, 2, 2, true},  {6, 3, 1, false},
                                 {8, 5, -3, true}};
  const uint32_t n = 200000;
  for (const OrbitalState& s : states) {
    CAPTURE(describe(s));
    const auto p = sample_on(test::backend(), make_orbital_tables(s, OrbitalPlacement::exact, n, 7));
    const Moments m = moments(p);
    check_moment("<r>", m.r, expect_r(s.n, s.l), m.var_r, n);
    check_moment("<r^2>", m.r2, expect_r2(s.n, s.l), m.var_r2, n);
    check_moment("<1/r>", m.inv_r, expect_inv_r(s.n), m.var_inv_r, n);
    check_moment("<z^2>", m.z2, expect_r2(s.n, s.l) * expect_cos2(s.l, std::abs(s.m)), m.var_z2, n);
    if (!s.real) check_moment("<x^2> - <y^2>", m.x2 - m.y2, 0.0, 2 * m.var_z2 + m.r2 * m.r2, n);
  }
}

TEST_CASE("radial nodes: the cloud is empty where R_nl vanishes") {
  const OrbitalState s{4, 1, 0, false};
  const uint32_t n = 400000;
  const auto p = sample_on(test::backend(), make_orbital_tables(s, OrbitalPlacement::exact, n, 3));
  const auto nodes = radial_nodes(s.n, s.l);
  REQUIRE(nodes.size() == 2);
  auto count_in = [&](double a, double b) {
    size_t c = 0;
    for (const auto& v : p) {
      const double r = std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
      c += r >= a && r < b;
    }
    return double(c);
  };
  for (double node : nodes) {
    CAPTURE(node);
    const double h = 0.1;
    const double at = count_in(node - h, node + h);
    const double want = n * radial_probability(s, node - h, node + h);
    CHECK(std::abs(at - want) <= 5 * std::sqrt(want) + 3);
    // A minimum of the radial histogram: both neighbouring shells hold far more.
    CHECK(count_in(node - 5 * h, node - 3 * h) > 4 * at);
    CHECK(count_in(node + 3 * h, node + 5 * h) > 4 * at);
  }
}

TEST_CASE("angular distributions pass a chi-square test against |Y_lm|^2") {
  const uint32_t n = 100000;
  {
    const OrbitalState s{3, 2, 1, false};
    const auto p = sample_on(test::backend(), make_orbital_tables(s, OrbitalPlacement::exact, n, 9));
    const int bins = 40;
    std::vector<double> counts(bins, 0), prob(bins);
    for (const auto& v : p) {
      const double ct = v.z / std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
      counts[std::min(bins - 1, int((ct + 1) * 0.5 * bins))] += 1;
    }
    for (int k = 0; k < bins; ++k)
      prob[k] = polar_probability(s, -1 + 2.0 * k / bins, -1 + 2.0 * (k + 1) / bins);
    int dof;
    const double chi = chi_square(counts, prob, n, dof);
    CAPTURE(dof);
    CHECK(chi < chi_critical(dof));
  }
  for (const OrbitalState& s : {OrbitalState{3, 2, -2, true}, OrbitalState{4, 3, 3, true}}) {
    CAPTURE(describe(s));
    const auto p = sample_on(test::backend(), make_orbital_tables(s, OrbitalPlacement::exact, n, 5));
    const int bins = 48;
    std::vector<double> counts(bins, 0), prob(bins);
    for (const auto& v : p) {
      double phi = std::atan2(v.y, v.x);
      if (phi < 0) phi += 2 * kPi;
      counts[std::min(bins - 1, int(phi / (2 * kPi) * bins))] += 1;
    }
    const double am = std::abs(s.m), sign = s.m > 0 ? 1.0 : -1.0;
    auto F = [&](double x) { return (x + sign * std::sin(2 * am * x) / (2 * am)) / (2 * kPi); };
    for (int k = 0; k < bins; ++k) prob[k] = F(2 * kPi * (k + 1) / bins) - F(2 * kPi * k / bins);
    int dof;
    const double chi = chi_square(counts, prob, n, dof);
    CAPTURE(dof);
    CHECK(chi < chi_critical(dof));
  }
}

TEST_CASE("shell placement (thesis Algorithm 2.1) puts exactly count particles near |psi|^2") {
  const OrbitalState s{3, 1, 0, false};
  const uint32_t n = 100000;
  const OrbitalTables t = make_orbital_tables(s, OrbitalPlacement::shells, n, 1);
  const auto p = sample_on(test::backend(), t);
  REQUIRE(p.size() == n);
  const Moments m = moments(p);
  // Stratified, so the spread is below Monte Carlo noise; the site grid's bias stays < 0.5 %.
  CHECK(m.r == doctest::Approx(expect_r(3, 1)).epsilon(5e-3));
  CHECK(m.r2 == doctest::Approx(expect_r2(3, 1)).epsilon(5e-3));
  CHECK(m.z2 == doctest::Approx(expect_r2(3, 1) * expect_cos2(1, 0)).epsilon(1e-2));
}

TEST_CASE("orbital_sample rejects bad input, naming the field") {
  Backend& b = test::backend();
  const OrbitalTables t = make_orbital_tables({2, 1, 1, true}, OrbitalPlacement::exact, 100, 1);
  auto tables = b.create<uint32_t>(t.cdf.size(), "tables");
  b.upload(tables, t.cdf);
  auto pos = b.create<Real4>(50, "positions");
  CHECK_THROWS_WITH_AS(b.orbital_sample(t.params, tables, pos),
                       doctest::Contains("invalid particles = 100"), Error);
  auto small = b.create<uint32_t>(10, "tables");
  OrbitalSampleParams p = t.params;
  p.count = 50;
  CHECK_THROWS_WITH_AS(b.orbital_sample(p, small, pos), doctest::Contains("tables size"), Error);
  p.radial_max_a0 = NAN;
  CHECK_THROWS_WITH_AS(b.orbital_sample(p, tables, pos), doctest::Contains("radial_max_a0"), Error);
  CHECK_THROWS_WITH_AS(make_orbital_tables({2, 2, 0}, OrbitalPlacement::exact, 1, 1),
                       doctest::Contains("invalid l = 2"), Error);
}
