#include "engine/verify/kernel_check.h"

#include <fmt/format.h>

#include <random>

#include "engine/core/enum_names.h"
#include "engine/core/error.h"
#include "engine/util/chi_square.h"
#include "engine/util/error_metrics.h"

namespace masav::verify {
namespace {

const CheckOutput* find(const CheckOutputs& outs, const std::string& name) {
  for (const auto& o : outs)
    if (o.name == name) return &o;
  return nullptr;
}

}  // namespace

const char* check_kind_name(CheckKind k) {
  static const char* const names[] = {"exact", "tolerance", "statistical"};
  return enum_name(k, names);
}

std::string Tolerance::describe() const {
  return fmt::format("rel L2 <= {:.3g}, each value within {:.3g} abs or {:.3g} rel", rel_l2,
                     max_abs, max_rel);
}

Verdict compare_exact(const CheckOutputs& got, const CheckOutputs& want) {
  Verdict v;
  v.pass = true;
  v.tolerance = "bit for bit";
  size_t total = 0, differ = 0;
  std::string first;
  for (const auto& w : want) {
    const CheckOutput* g = find(got, w.name);
    const size_t n = w.words.size();
    total += n;
    if (!g || g->words.size() != n) {
      v.pass = false;
      differ += n;
      first = first.empty()
                  ? fmt::format("{}: {} words against {}", w.name, g ? g->words.size() : 0, n)
                  : first;
      continue;
    }
    for (size_t i = 0; i < n; ++i)
      if (g->words[i] != w.words[i]) {
        if (first.empty())
          first = fmt::format("{}[{}] = {} against {}", w.name, i, g->words[i], w.words[i]);
        ++differ;
      }
  }
  v.pass = v.pass && differ == 0;
  v.metrics = fmt::format("{} of {} words differ{}", differ, total,
                          first.empty() ? "" : " (first: " + first + ")");
  v.numbers = {{"words", double(total)}, {"differ", double(differ)}};
  return v;
}

Verdict compare_tolerance(const CheckOutputs& got, const CheckOutputs& want, const Tolerance& tol) {
  Verdict v;
  v.pass = true;
  v.tolerance = tol.describe();
  double rel_l2 = 0, max_abs = 0, max_rel = 0;
  size_t non_finite = 0;
  for (const auto& w : want) {
    const CheckOutput* g = find(got, w.name);
    if (!g || g->reals.size() != w.reals.size()) {
      v.pass = false;
      v.metrics =
          fmt::format("{}: {} values against {}", w.name, g ? g->reals.size() : 0, w.reals.size());
      return v;
    }
    const ErrorStats e =
        compare(std::span<const double>(g->reals), std::span<const double>(w.reals), tol.rel_floor);
    rel_l2 = std::max(rel_l2, e.rel_l2);
    max_abs = std::max(max_abs, e.max_abs);
    max_rel = std::max(max_rel, e.max_rel);
    non_finite += e.non_finite;
  }
  v.pass =
      non_finite == 0 && rel_l2 <= tol.rel_l2 && (max_abs <= tol.max_abs || max_rel <= tol.max_rel);
  v.metrics = fmt::format("rel L2 {:.3g}, max abs {:.3g}, max rel {:.3g}{}", rel_l2, max_abs,
                          max_rel, non_finite ? fmt::format(", {} non-finite", non_finite) : "");
  v.numbers = {{"rel_l2", rel_l2},          {"max_abs", max_abs},
               {"max_rel", max_rel},        {"non_finite", double(non_finite)},
               {"tol_rel_l2", tol.rel_l2},  {"tol_max_abs", tol.max_abs},
               {"tol_max_rel", tol.max_rel}};
  return v;
}

Verdict compare_chi_square(const CheckOutputs& got, const CheckOutputs& want, double min_p) {
  Verdict v;
  v.pass = true;
  v.tolerance = fmt::format("two-sample chi-square p >= {:.3g}", min_p);
  double worst_p = 1, stat = 0, dof = 0;
  for (const auto& w : want) {
    const CheckOutput* g = find(got, w.name);
    auto as_reals = [](const CheckOutput& o) {
      return o.reals.empty() ? std::vector<double>(o.words.begin(), o.words.end()) : o.reals;
    };
    const std::vector<double> a = g ? as_reals(*g) : std::vector<double>{};
    const std::vector<double> b = as_reals(w);
    if (a.size() != b.size()) {
      v.pass = false;
      v.metrics = fmt::format("{}: {} bins against {}", w.name, a.size(), b.size());
      return v;
    }
    const ChiSquare c = chi_square_two_sample(a, b);
    if (c.p_value < worst_p || dof == 0) worst_p = c.p_value, stat = c.statistic, dof = c.dof;
  }
  v.pass = worst_p >= min_p;
  v.metrics = fmt::format("chi-square {:.4g} with {} dof, p = {:.3g}", stat, dof, worst_p);
  v.numbers = {{"chi_square", stat}, {"dof", dof}, {"p_value", worst_p}, {"min_p", min_p}};
  return v;
}

KernelCheck exact_check(std::string kernel,
                        std::function<CheckOutputs(Backend&, const CheckInputs&)> run) {
  return {std::move(kernel), CheckKind::exact, std::move(run),
          [](const CheckOutputs& g, const CheckOutputs& w, const CheckInputs&) {
            return compare_exact(g, w);
          }};
}

KernelCheck tolerance_check(std::string kernel, Tolerance tol,
                            std::function<CheckOutputs(Backend&, const CheckInputs&)> run) {
  return {std::move(kernel), CheckKind::tolerance, std::move(run),
          [tol](const CheckOutputs& g, const CheckOutputs& w, const CheckInputs&) {
            return compare_tolerance(g, w, tol);
          }};
}

KernelCheck chi_square_check(std::string kernel, double min_p,
                             std::function<CheckOutputs(Backend&, const CheckInputs&)> run) {
  return {std::move(kernel), CheckKind::statistical, std::move(run),
          [min_p](const CheckOutputs& g, const CheckOutputs& w, const CheckInputs&) {
            return compare_chi_square(g, w, min_p);
          }};
}

KernelCheck exact_check(KernelId kernel,
                        std::function<CheckOutputs(Backend&, const CheckInputs&)> run) {
  return exact_check(std::string(kernel_name(kernel)), std::move(run));
}

KernelCheck tolerance_check(KernelId kernel, Tolerance tol,
                            std::function<CheckOutputs(Backend&, const CheckInputs&)> run) {
  return tolerance_check(std::string(kernel_name(kernel)), tol, std::move(run));
}

KernelCheck chi_square_check(KernelId kernel, double min_p,
                             std::function<CheckOutputs(Backend&, const CheckInputs&)> run) {
  return chi_square_check(std::string(kernel_name(kernel)), min_p, std::move(run));
}

std::vector<Vec4f> check_points(const CheckInputs& in) {
  std::mt19937_64 rng(in.seed * 0x9E3779B97F4A7C15ull + 17);
  Vec3f lo{0, 0, 0}, size{1, 1, 1};
  if (in.grid) {
    const GridParams& g = *in.grid;
    lo = g.origin;
    size = {g.cell_size * float(g.dims.x), g.cell_size * float(g.dims.y),
            g.cell_size * float(g.dims.z)};
  }
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<Vec4f> p(in.points);
  for (uint32_t i = 0; i < in.points; ++i)
    p[i] = {lo.x + size.x * u(rng), lo.y + size.y * u(rng), lo.z + size.z * u(rng), float(i)};
  return p;
}

}  // namespace masav::verify
