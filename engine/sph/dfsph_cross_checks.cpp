// Cross-checks of the DFSPH kernels (dfsph_factor, dfsph_rate, dfsph_correct) on the SPH check
// case (engine/sph/sph_check_case.h) with the dfsph model: box walls on, some particles pinned
// or heavy, each kernel walking every candidate and over sph_density's neighbour row masks.
// dfsph_rate and dfsph_correct get identical smooth fields made on the host (density, factor,
// kappas), so each checks its kernel alone. Tolerances measured on lavapipe with about 10x
// margin (see the comment at each check).
#include <fmt/format.h>

#include <cmath>
#include <string>

#include "engine/sph/dfsph_case_buffers.h"
#include "engine/sph/sph_check_case.h"
#include "engine/sph/sph_cross_checks.h"
#include "engine/sph/sph_kernel_calls.h"
#include "engine/util/error_metrics.h"

namespace masav::verify {
namespace {

// The check case's buffers with sph_density's row masks, and the DFSPH buffers.
struct DfsphCase {
  SphCheckCase cs;
  SphCaseBuffers s;
  DfsphCaseBuffers dfsph;
  std::vector<Vec4f> sorted_pos;  // fp32, as the backend holds them
};

DfsphCase make_dfsph_case(Backend& b, const CheckInputs& in) {
  DfsphCase d{make_sph_check_case(in, SphPressureModel::dfsph)};
  d.s = upload_sph_case(b, d.cs.params, d.cs.positions, d.cs.velocities, "check dfsph");
  d.dfsph = make_dfsph_buffers(b, d.cs.params.n, "check dfsph");
  sph_density(
      b, d.cs.params,
      {&d.s.sorted_pos, d.s.view(), &d.s.density, &d.s.pressure, &d.s.stats, &d.s.neighbor_rows});
  d.sorted_pos = b.download_f32(d.s.sorted_pos);
  return d;
}

DfsphIO io_of(DfsphCase& d, bool masked) {
  return dfsph_io(d.s, d.dfsph, masked);
}

// A smooth field over the sorted particles: scale (1 + amplitude sin(97 x + 61 y + 83 z)).
std::vector<double> field(const std::vector<Vec4f>& pos, double scale, double amplitude,
                          double phase) {
  std::vector<double> f(pos.size());
  for (size_t i = 0; i < pos.size(); ++i)
    f[i] =
        scale *
        (1.0 + amplitude * std::sin(97.0 * pos[i].x + 61.0 * pos[i].y + 83.0 * pos[i].z + phase));
  return f;
}

// The factor's scale: 1 / (30 (grad / 4)^2), a particle with 30 neighbours at q = 1/2.
double factor_scale(const SphStepParams& p) {
  const double g = device_params<double>(DfsphParams{p}).grad / 4.0;
  return 1.0 / (30.0 * g * g);
}

}  // namespace

std::vector<KernelCheck> dfsph_checks() {
  std::vector<KernelCheck> c;
  // The factor to 1e-5 (rel L2) and each value to 1e-4 of itself: a reciprocal of a sum of
  // ~30 positive squares (lavapipe: 1e-6, 1.1e-5).
  c.push_back(per_output_check(
      KernelId::dfsph_factor, {{"factor", {1e-5, 0, 1e-4, 1e-30}}},
      [](Backend& b, const CheckInputs& in) {
        DfsphCase d = make_dfsph_case(b, in);
        CheckOutputs out;
        for (const bool masked : {false, true}) {
          dfsph_factor(b, DfsphParams{d.cs.params}, io_of(d, masked));
          out.push_back(
              {masked ? "factor over row masks" : "factor", {}, b.download(d.dfsph.factor)});
        }
        return out;
      }));
  // Both solves, a first iteration (the kappa sum rescaled) into residual slot 3: kappa and its
  // sum to 2e-5 (rel L2) and 2e-4 of their RMS each (a rate is a sum of ~30 terms that partly
  // cancel, then clamped at 0; lavapipe: 2e-6, 1e-5); the residual sum (integer units) to 1e-4.
  c.push_back(per_output_check(
      KernelId::dfsph_rate,
      {{"kappa", {2e-5, 0, 2e-4, 1.0}, true}, {"residual", {1e-4, 0, 1e-4, 1.0}}},
      [](Backend& b, const CheckInputs& in) {
        DfsphCase d = make_dfsph_case(b, in);
        const double f0 = factor_scale(d.cs.params);
        CheckOutputs out;
        for (const DfsphSolve solve : {DfsphSolve::density, DfsphSolve::divergence})
          for (const bool masked : {false, true}) {
            b.upload(d.s.density, field(d.sorted_pos, 1000.0, 0.02, 0.0));
            b.upload(d.dfsph.factor, field(d.sorted_pos, f0, 0.2, 1.0));
            b.upload(d.dfsph.kappa_sum, field(d.sorted_pos, 1e-4, 0.5, 2.0));
            b.fill(d.dfsph.residual, 0u);
            DfsphParams p{d.cs.params, solve, 1e-3, 3, true, 0.5, 20};
            dfsph_rate(b, p, io_of(d, masked));
            const std::string v =
                fmt::format("{}{}", solve == DfsphSolve::density ? "density" : "divergence",
                            masked ? " over row masks" : "");
            out.push_back({"kappa " + v, {}, b.download(d.dfsph.kappa)});
            out.push_back({"kappa sum " + v, {}, b.download(d.dfsph.kappa_sum)});
            const auto w = b.download(d.dfsph.residual);
            out.push_back({"residual " + v, {}, {double(uint64_t(w[7]) << 32 | w[6])}});
          }
        return out;
      }));
  // The velocity change, plain and as a warm start (half the kappas), to 2e-5 (rel L2) and
  // 3e-4 of its RMS each (lavapipe: 2e-6, 2e-5).
  c.push_back(per_output_check(
      KernelId::dfsph_correct, {{"dv", {2e-5, 0, 3e-4, 1.0}, true}},
      [](Backend& b, const CheckInputs& in) {
        DfsphCase d = make_dfsph_case(b, in);
        const auto v0 = b.download(d.s.sorted_vel);
        CheckOutputs out;
        for (const bool first : {false, true})
          for (const bool masked : {false, true}) {
            b.upload(d.s.sorted_vel, v0);
            b.upload(d.dfsph.kappa, field(d.sorted_pos, 1e-4, 0.5, 0.5));
            DfsphParams p{d.cs.params, DfsphSolve::density, 1e-3, 0, first, 0.5, 0};
            dfsph_correct(b, p, io_of(d, masked));
            const auto v1 = b.download(d.s.sorted_vel);
            std::vector<double> dv;
            for (size_t i = 0; i < v1.size(); ++i)
              dv.insert(dv.end(), {v1[i].x - v0[i].x, v1[i].y - v0[i].y, v1[i].z - v0[i].z});
            out.push_back(
                {fmt::format("dv{}{}", first ? " warm start" : "", masked ? " over row masks" : ""),
                 {},
                 dv});
          }
        return out;
      }));
  return c;
}

}  // namespace masav::verify
