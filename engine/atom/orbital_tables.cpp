#include "engine/atom/orbital_tables.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numeric>

#include "engine/atom/hydrogen_math.h"
#include "engine/atom/quadrature.h"
#include "engine/core/error.h"

namespace masav::atom {
namespace {

constexpr double kPi = 3.14159265358979323846;

struct RadialFn {
  int n, l;
  double log_norm;
  double operator()(double r) const {
    const double R = hydrogen::radial(n, l, r, log_norm, [](double x) { return std::exp(x); });
    return r * r * R * R;
  }
};

RadialFn radial_fn(const OrbitalState& s) { return RadialFn{s.n, s.l, radial_log_norm(s.n, s.l)}; }

double polar_fn(const OrbitalState& s, double x) {
  const double p =
      hydrogen::legendre_normalized(s.l, std::abs(s.m), x, [](double v) { return std::sqrt(v); });
  return 2.0 * kPi * p * p;  // integrates to 1 over [-1, 1]
}

// Radius beyond which the radial mass is below tail * total, found by walking out in segments.
double radial_extent(const OrbitalState& s, double tail) {
  const RadialFn f = radial_fn(s);
  const double w = 0.125 * s.n;
  std::vector<double> masses;
  double total = 0;
  for (int i = 0; i < 1000000; ++i) {
    const double m = gauss_legendre8(f, i * w, (i + 1) * w);
    masses.push_back(m);
    total += m;
    if ((i + 1) * w > 3.0 * expect_r(s.n, s.l) && m < 1e-22) break;
  }
  double beyond = 0;
  size_t k = masses.size();
  while (k > 0 && beyond + masses[k - 1] <= tail * total) beyond += masses[--k];
  return std::max<double>(k, 1) * w;
}

// Running sums of bin masses, normalised and rounded to integers out of 2^24.
std::vector<uint32_t> quantize_cdf(const std::vector<double>& masses) {
  const double total = std::accumulate(masses.begin(), masses.end(), 0.0);
  std::vector<uint32_t> cdf(masses.size() + 1, 0);
  double run = 0;
  for (size_t k = 0; k < masses.size(); ++k) {
    run += masses[k];
    cdf[k + 1] = uint32_t(std::llround(run / total * kCdfOne));
  }
  cdf.back() = kCdfOne;
  for (size_t k = 1; k < cdf.size(); ++k) cdf[k] = std::max(cdf[k], cdf[k - 1]);
  return cdf;
}

std::vector<double> radial_masses(const OrbitalState& s, double r_max, uint32_t bins) {
  const RadialFn f = radial_fn(s);
  std::vector<double> m(bins);
  for (uint32_t k = 0; k < bins; ++k)
    m[k] = gauss_legendre8(f, r_max * k / bins, r_max * (k + 1) / bins);
  return m;
}

std::vector<double> polar_masses(const OrbitalState& s, uint32_t bins) {
  std::vector<double> m(bins);
  for (uint32_t k = 0; k < bins; ++k)
    m[k] = gauss_legendre8([&](double x) { return polar_fn(s, x); }, -1.0 + 2.0 * k / bins,
                           -1.0 + 2.0 * (k + 1) / bins);
  return m;
}

// Mass of cos^2(|m| phi) (or sin^2) over [a, b] in phi, normalised over [0, 2 pi).
double azimuth_mass(const OrbitalState& s, double a, double b) {
  if (!s.real || s.m == 0) return (b - a) / (2.0 * kPi);
  const double am = std::abs(s.m), sign = s.m > 0 ? 1.0 : -1.0;
  auto F = [&](double x) { return (x + sign * std::sin(2.0 * am * x) / (2.0 * am)) / (2.0 * kPi); };
  return F(b) - F(a);
}

void check_table_options(const TableOptions& o, OrbitalPlacement placement) {
  auto bins = [](const char* field, uint32_t v, uint32_t lo, uint32_t hi) {
    if (v < lo || v > hi)
      throw_invalid("orbital tables", field, std::to_string(v), fmt::format("in [{}, {}]", lo, hi));
  };
  if (placement == OrbitalPlacement::exact) {
    bins("radial_bins", o.radial_bins, 16, 1u << 20);
    bins("polar_bins", o.polar_bins, 16, 1u << 20);
    bins("azimuth_bins", o.azimuth_bins, 16, 1u << 20);
  } else {
    bins("shells", o.shells, 1, 4096);
    bins("shell_polar", o.shell_polar, 1, 4096);
    bins("shell_azimuth", o.shell_azimuth, 1, 4096);
    const uint64_t sites = uint64_t(o.shells) * o.shell_polar * o.shell_azimuth;
    if (sites > (1u << 24))
      throw_invalid("orbital tables", "shells * shell_polar * shell_azimuth",
                    std::to_string(sites), "at most 2^24 sites");
  }
  if (!(o.tail_mass > 0 && o.tail_mass < 1e-3))
    throw_invalid("orbital tables", "tail_mass", fmt::format("{}", o.tail_mass), "in (0, 1e-3)");
}

OrbitalTables shell_tables(const OrbitalState& s, uint32_t count, const TableOptions& o,
                           double r_max) {
  const std::vector<double> pr = radial_masses(s, r_max, o.shells);
  const std::vector<double> pt = polar_masses(s, o.shell_polar);
  std::vector<double> pp(o.shell_azimuth);
  for (uint32_t k = 0; k < o.shell_azimuth; ++k)
    pp[k] = azimuth_mass(s, 2.0 * kPi * k / o.shell_azimuth, 2.0 * kPi * (k + 1) / o.shell_azimuth);
  const double tr = std::accumulate(pr.begin(), pr.end(), 0.0);
  const double tt = std::accumulate(pt.begin(), pt.end(), 0.0);
  const size_t sites = size_t(o.shells) * o.shell_polar * o.shell_azimuth;
  // Systematic rounding: site k gets round(S_k) - round(S_{k-1}) particles, S_k the running sum
  // of expected counts. Every site gets the floor or the ceiling of its expectation, the total
  // is exactly `count`, and a run of faint sites holding one particle's worth of probability
  // still gets about one particle (rounding each site alone would empty the tails).
  std::vector<uint32_t> counts(sites);
  double run = 0;
  uint64_t prev = 0;
  for (size_t i = 0; i < sites; ++i) {
    const size_t ir = i / (size_t(o.shell_polar) * o.shell_azimuth);
    const size_t it = (i / o.shell_azimuth) % o.shell_polar, ip = i % o.shell_azimuth;
    run += double(count) * pr[ir] / tr * pt[it] / tt * pp[ip];
    const uint64_t upto = i + 1 == sites ? count : std::min<uint64_t>(count, std::llround(run));
    counts[i] = uint32_t(upto > prev ? upto - prev : 0);
    prev = std::max(prev, upto);
  }
  OrbitalTables t;
  t.cdf.assign(sites + 1, 0);
  for (size_t i = 0; i < sites; ++i) t.cdf[i + 1] = t.cdf[i] + counts[i];
  t.params.radial_bins = o.shells;
  t.params.polar_bins = o.shell_polar;
  t.params.azimuth_bins = o.shell_azimuth;
  return t;
}

}  // namespace

OrbitalTables make_orbital_tables(const OrbitalState& s, OrbitalPlacement placement,
                                  uint32_t count, uint64_t seed, const TableOptions& o) {
  validate_state(s, "orbital_sample");
  check_table_options(o, placement);
  const double r_max = radial_extent(s, o.tail_mass);
  OrbitalTables t;
  if (placement == OrbitalPlacement::shells) {
    t = shell_tables(s, count, o, r_max);
  } else {
    t.cdf = quantize_cdf(radial_masses(s, r_max, o.radial_bins));
    const auto polar = quantize_cdf(polar_masses(s, o.polar_bins));
    t.cdf.insert(t.cdf.end(), polar.begin(), polar.end());
    t.params.radial_bins = o.radial_bins;
    t.params.polar_bins = o.polar_bins;
    t.params.azimuth_bins = 0;
    if (s.real && s.m != 0) {
      // psi in [0, pi) with density cos^2(psi); phi = (k pi + psi + offset) / |m|.
      std::vector<double> m(o.azimuth_bins);
      for (uint32_t k = 0; k < o.azimuth_bins; ++k) {
        const double a = kPi * k / o.azimuth_bins, b = kPi * (k + 1) / o.azimuth_bins;
        m[k] = (b - a) + 0.5 * (std::sin(2.0 * b) - std::sin(2.0 * a));
      }
      const auto az = quantize_cdf(m);
      t.cdf.insert(t.cdf.end(), az.begin(), az.end());
      t.params.azimuth_bins = o.azimuth_bins;
      t.params.azimuth_periods = uint32_t(2 * std::abs(s.m));
      t.params.azimuth_offset = s.m > 0 ? 0.0f : float(kPi / 2);
    }
  }
  t.params.count = count;
  t.params.seed = seed;
  t.params.placement = placement;
  t.params.radial_max_a0 = float(r_max);
  t.truncated_mass = radial_probability(s, r_max, 10.0 * r_max + 100.0);
  return t;
}

double radial_probability(const OrbitalState& s, double a, double b) {
  if (!(b > a)) return 0.0;
  const int pieces = std::max(4, int(std::ceil((b - a) / (0.05 * s.n))));
  return integrate(radial_fn(s), a, b, std::min(pieces, 200000));
}

double polar_probability(const OrbitalState& s, double a, double b) {
  if (!(b > a)) return 0.0;
  return integrate([&](double x) { return polar_fn(s, x); }, a, b, 64);
}

double radial_quantile(const OrbitalState& s, double p) {
  validate_state(s, "radial_quantile");
  if (!(p > 0 && p < 1 - 1e-12))
    throw_invalid("radial_quantile", "probability", fmt::format("{}", p), "in (0, 1 - 1e-12)");
  const RadialFn f = radial_fn(s);
  const double w = 0.05 * s.n;
  double cum = 0;
  for (int i = 0;; ++i) {
    const double m = gauss_legendre8(f, i * w, (i + 1) * w);
    if (cum + m >= p) {  // bisect inside this segment
      double lo = i * w, hi = (i + 1) * w;
      for (int it = 0; it < 60; ++it) {
        const double mid = 0.5 * (lo + hi);
        (cum + gauss_legendre8(f, i * w, mid) < p ? lo : hi) = mid;
      }
      return 0.5 * (lo + hi);
    }
    cum += m;
  }
}

double box_half_width(const OrbitalState& s, double p) { return radial_quantile(s, p); }

}  // namespace masav::atom
