#include "engine/util/chi_square.h"

#include <cmath>

#include "engine/core/error.h"

namespace masav {
namespace {

// Series for P(s, x), good for x < s + 1.
double gamma_p_series(double s, double x) {
  double term = 1.0 / s, sum = term;
  for (int k = 1; k < 10000; ++k) {
    term *= x / (s + k);
    sum += term;
    if (std::abs(term) < std::abs(sum) * 1e-16) break;
  }
  return sum * std::exp(-x + s * std::log(x) - std::lgamma(s));
}

// Continued fraction for Q(s, x) (modified Lentz), good for x >= s + 1.
double gamma_q_fraction(double s, double x) {
  constexpr double tiny = 1e-300;
  double b = x + 1.0 - s, c = 1.0 / tiny, d = 1.0 / b, h = d;
  for (int k = 1; k < 10000; ++k) {
    const double an = -k * (k - s);
    b += 2.0;
    d = an * d + b;
    if (std::abs(d) < tiny) d = tiny;
    c = b + an / c;
    if (std::abs(c) < tiny) c = tiny;
    d = 1.0 / d;
    const double delta = d * c;
    h *= delta;
    if (std::abs(delta - 1.0) < 1e-16) break;
  }
  return std::exp(-x + s * std::log(x) - std::lgamma(s)) * h;
}

}  // namespace

double gamma_q(double s, double x) {
  if (!(s > 0) || !(x >= 0)) throw Error("", "gamma_q", "needs s > 0 and x >= 0", "internal error");
  if (x == 0) return 1.0;
  return x < s + 1.0 ? 1.0 - gamma_p_series(s, x) : gamma_q_fraction(s, x);
}

ChiSquare chi_square_two_sample(std::span<const double> a, std::span<const double> b) {
  if (a.size() != b.size())
    throw Error("", "chi_square", "histograms with different bin counts",
                "compare histograms of the same binning");
  double na = 0, nb = 0;
  for (size_t i = 0; i < a.size(); ++i) na += a[i], nb += b[i];
  ChiSquare r;
  if (na <= 0 || nb <= 0) return r;
  const double ka = std::sqrt(nb / na), kb = std::sqrt(na / nb);
  int bins = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    if (a[i] == 0 && b[i] == 0) continue;
    const double d = ka * a[i] - kb * b[i];
    r.statistic += d * d / (a[i] + b[i]);
    ++bins;
  }
  r.dof = bins - (na == nb ? 1 : 0);
  r.p_value = r.dof > 0 ? gamma_q(0.5 * r.dof, 0.5 * r.statistic) : 1.0;
  return r;
}

}  // namespace masav
