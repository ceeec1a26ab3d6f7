#include "engine/atom/orbital.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "engine/atom/hydrogen_math.h"
#include "engine/core/error.h"

namespace masav::atom {
namespace {

constexpr double kPi = 3.14159265358979323846;

double dsqrt(double x) {
  return std::sqrt(x);
}
double dexp(double x) {
  return std::exp(x);
}

// Thesis Table 2.1.
constexpr OrbitalState kPresets[10] = {{1, 0, 0}, {2, 0, 0}, {2, 1, 0}, {2, 1, 1}, {3, 0, 0},
                                       {3, 1, 0}, {3, 1, 1}, {3, 2, 0}, {3, 2, 1}, {3, 2, 2}};

}  // namespace

void validate_state(const OrbitalState& s, std::string_view where) {
  if (s.n < 1 || s.n > kMaxN)
    throw_invalid(where, "n", std::to_string(s.n), fmt::format("an integer in [1, {}]", kMaxN));
  if (s.l < 0 || s.l >= s.n)
    throw_invalid(where, "l", std::to_string(s.l),
                  fmt::format("an integer in [0, n - 1] = [0, {}] for n = {}", s.n - 1, s.n));
  if (s.m < -s.l || s.m > s.l)
    throw_invalid(where, "m", std::to_string(s.m),
                  fmt::format("an integer in [-l, l] = [{}, {}] for l = {}", -s.l, s.l, s.l));
}

const std::vector<std::string>& preset_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> v;
    for (int i = 1; i <= 10; ++i) v.push_back(fmt::format("state{}", i));
    return v;
  }();
  return names;
}

OrbitalState preset_state(std::string_view name) {
  const auto& names = preset_names();
  for (size_t i = 0; i < names.size(); ++i)
    if (names[i] == name) return kPresets[i];
  throw_invalid("orbital", "state", std::string(name),
                "one of state1 .. state10 (thesis Table 2.1)");
}

std::string describe(const OrbitalState& s) {
  return fmt::format("n={} l={} m={} ({})", s.n, s.l, s.m, s.real ? "real" : "complex");
}

double radial_log_norm(int n, int l) {
  return 1.5 * std::log(2.0 / n) +
         0.5 * (std::lgamma(double(n - l)) - std::log(2.0 * n) - std::lgamma(double(n + l + 1)));
}

double radial_R(int n, int l, double r) {
  return hydrogen::radial(n, l, r, radial_log_norm(n, l), dexp);
}

double angular_density(const OrbitalState& s, double cos_theta, double phi) {
  const int am = std::abs(s.m);
  const double p = hydrogen::legendre_normalized(s.l, am, cos_theta, dsqrt);
  double a = p * p;
  if (s.real && s.m > 0) a *= 2.0 * std::cos(am * phi) * std::cos(am * phi);
  if (s.real && s.m < 0) a *= 2.0 * std::sin(am * phi) * std::sin(am * phi);
  return a;
}

double density(const OrbitalState& s, double r, double cos_theta, double phi) {
  const double R = radial_R(s.n, s.l, r);
  return R * R * angular_density(s, cos_theta, phi);
}

double peak_density(const OrbitalState& s) {
  // Separable: the maximum is max_r R^2 times max over angles of |Y|^2.
  double rmax = 0, amax = 0;
  const double r_end = 4.0 * s.n * s.n + 20.0;
  for (int i = 0; i <= 20000; ++i) {
    const double R = radial_R(s.n, s.l, r_end * i / 20000.0);
    rmax = std::max(rmax, R * R);
  }
  for (int i = 0; i <= 4000; ++i) {
    const double ct = -1.0 + 2.0 * i / 4000.0;
    const double phi = s.real ? (s.m > 0 ? 0.0 : kPi / (2.0 * std::abs(s.m))) : 0.0;
    amax = std::max(amax, angular_density(s, ct, phi));
  }
  return rmax * amax;
}

double expect_r(int n, int l) {
  return 0.5 * (3.0 * n * n - l * (l + 1.0));
}
double expect_r2(int n, int l) {
  return 0.5 * n * n * (5.0 * n * n + 1.0 - 3.0 * l * (l + 1.0));
}
double expect_inv_r(int n) {
  return 1.0 / (double(n) * n);
}
double expect_cos2(int l, int m) {
  return (2.0 * l * l + 2.0 * l - 1.0 - 2.0 * m * m) / ((2.0 * l - 1.0) * (2.0 * l + 3.0));
}

std::vector<double> radial_nodes(int n, int l) {
  // Bracket sign changes of L_k^{2l+1}(2r/n) on a fine grid, then bisect.
  const int k = n - l - 1;
  std::vector<double> roots;
  if (k <= 0) return roots;
  auto f = [&](double r) { return hydrogen::laguerre(k, double(2 * l + 1), 2.0 * r / n); };
  const double r_end = 4.0 * n * n + 20.0;
  const int steps = 200000;
  double a = 0, fa = f(0);
  for (int i = 1; i <= steps && int(roots.size()) < k; ++i) {
    const double b = r_end * i / steps, fb = f(b);
    if ((fa < 0) != (fb < 0)) {
      double lo = a, hi = b, flo = fa;
      for (int it = 0; it < 200 && hi - lo > 1e-13 * std::max(1.0, hi); ++it) {
        const double mid = 0.5 * (lo + hi), fm = f(mid);
        if ((fm < 0) == (flo < 0))
          lo = mid, flo = fm;
        else
          hi = mid;
      }
      roots.push_back(0.5 * (lo + hi));
    }
    a = b;
    fa = fb;
  }
  return roots;
}

}  // namespace masav::atom
