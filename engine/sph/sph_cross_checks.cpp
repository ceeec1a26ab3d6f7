// Cross-checks of the SPH kernels (sph_density, sph_forces, sph_integrate) before an SPH scene
// renders: a jittered lattice of fluid with random velocities (some particles pinned or heavy,
// box walls on), made on the host from Philox and uploaded identically to both backends, sorted
// into the hash grid there. The tolerances are those of tests/test_sph_kernels.cpp, measured on
// lavapipe with about 10x margin: fp32 backends hold positions to ~6e-8 relative, densities
// agree to 1e-7 (rel L2), accelerations -- sums of ~30 terms that largely cancel, except beside
// a wall -- to ~1.5e-6 of their RMS.
#include "engine/sph/sph_cross_checks.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "engine/grid/hash_grid.h"
#include "engine/kernels/philox.h"
#include "engine/kernels/sph_kernels.h"
#include "engine/sph/sph_case_buffers.h"
#include "engine/sph/sph_check_case.h"
#include "engine/sph/sph_kernel_calls.h"
#include "engine/sph/sph_particles.h"
#include "engine/util/error_metrics.h"

namespace masav::verify {
namespace {

// Philox stream of the integrator check's inputs (the case uses 11 and 12).
constexpr uint64_t kStageStream = 13;

const SphPressureModel kModels[] = {SphPressureModel::wcsph, SphPressureModel::thesis,
                                    SphPressureModel::dfsph};

// A check's run over both pressure models: the case of each model sorted into its grid on the
// backend, then `body` runs the kernel and appends outputs named with the model.
template <class Body>
std::function<CheckOutputs(Backend&, const CheckInputs&)> for_each_model(Body body) {
  return [body](Backend& b, const CheckInputs& in) {
    CheckOutputs out;
    for (SphPressureModel model : kModels) {
      const SphCheckCase cs = make_sph_check_case(in, model);
      SphCaseBuffers s = upload_sph_case(b, cs.params, cs.positions, cs.velocities, "check sph");
      body(b, cs, s, to_string(model), out);
    }
    return out;
  };
}

}  // namespace

std::vector<KernelCheck> sph_checks() {
  std::vector<KernelCheck> c;
  // Densities to 1e-6 (rel L2) and 5e-6 of each value; pressure amplifies density errors by the
  // equation of state's slope, so it is held to 1e-4 (rel L2) and each value to 1e-3 of the
  // RMS pressure (+1 Pa).
  c.push_back(per_output_check(
      KernelId::sph_density,
      {{"density", {1e-6, 0, 5e-6, 1.0}}, {"pressure", {1e-4, 0, 1.0, 1e-3}, true, 1.0}},
      for_each_model([](Backend& b, const SphCheckCase& cs, SphCaseBuffers& s, const std::string& m,
                        CheckOutputs& out) {
        sph_density(b, cs.params, {&s.sorted_pos, s.view(), &s.density, &s.pressure, &s.stats});
        out.push_back({"density " + m, {}, b.download(s.density)});
        out.push_back({"pressure " + m, {}, b.download(s.pressure)});
      })));
  // Accelerations to 1e-5 (rel L2) and each component to 2e-4 of the RMS acceleration (lavapipe
  // measured 1.5e-6 and 2.5e-5: the particles beside a wall carry the largest accelerations, the
  // uncancelled push of their images, and their fp32 rounding sets both); the neighbour counts
  // (accel w) exactly. Both backends get the same density and pressure
  // (a smooth field made on the host), so this checks the force kernel alone -- walking every
  // candidate, and over the neighbour row masks sph_density records at these positions; each
  // reading the four arrays, and the same field as a neighbour state.
  c.push_back(per_output_check(
      KernelId::sph_forces, {{"accel", {1e-5, 0, 2e-4, 1.0}, true}, {"neighbours", {0, 0, 0, 1.0}}},
      for_each_model([](Backend& b, const SphCheckCase& cs, SphCaseBuffers& s, const std::string& m,
                        CheckOutputs& out) {
        sph_density(b, cs.params,
                    {&s.sorted_pos, s.view(), &s.density, &s.pressure, &s.stats, &s.neighbor_rows});
        // Identical density and pressure on both backends: the rest density everywhere plus
        // a smooth field, so the pressure force is not trivial.
        std::vector<double> rho(cs.params.n), pr(cs.params.n);
        const auto sp = b.download_f32(s.sorted_pos);
        for (uint32_t i = 0; i < cs.params.n; ++i) {
          rho[i] = 1000.0 * (1.0 + 0.05 * std::sin(97.0 * sp[i].x + 61.0 * sp[i].y));
          pr[i] = 3000.0 * (1.0 + std::cos(83.0 * sp[i].z));
        }
        b.upload(s.density, rho);
        b.upload(s.pressure, pr);
        // The same field as the neighbour state sph_density would write (kSphStateStride).
        const auto sv = b.download_f32(s.sorted_vel);
        std::vector<Vec4d> records(size_t(kSphStateStride) * cs.params.n);
        for (uint32_t i = 0; i < cs.params.n; ++i) {
          records[kSphStateStride * i] = {sp[i].x, sp[i].y, sp[i].z, rho[i]};
          records[kSphStateStride * i + 1] = {sv[i].x, sv[i].y, sv[i].z,
                                              sph::pressure_over_rho2(pr[i], rho[i])};
        }
        auto state = b.create<Real4>(records.size(), "check sph neighbour state");
        b.upload(state, records);
        for (const bool over_state : {false, true})
          for (const bool masked : {false, true}) {
            SphForcesIO io{
                &s.sorted_pos, &s.sorted_vel, &s.density, &s.pressure,
                s.view(),      &s.accel,      &s.stats,   masked ? &s.neighbor_rows : nullptr};
            io.neighbor_state = over_state ? &state : nullptr;
            sph_forces(b, cs.params, io);
            const auto a = b.download(s.accel);
            std::vector<double> w(a.size());
            for (size_t i = 0; i < a.size(); ++i) w[i] = a[i].w;
            std::string variant = masked ? m + " over row masks" : m;
            if (over_state)
              variant += masked ? " and the neighbour state" : " over the neighbour state";
            out.push_back({"neighbours " + variant, {}, w});
            out.push_back({"accel " + variant, {}, xyz_components(a)});
          }
      })));
  // Every integrator stage: velocities within 5e-5 m/s, positions within 1e-6 m, the RK4
  // velocity sums within 1e-4 (dt = 2 ms, accelerations up to 30 m/s^2), walls on.
  c.push_back(per_output_check(
      KernelId::sph_integrate,
      {{"v ", {1e-5, 5e-5, 0, 1.0}},
       {"x ", {1e-6, 1e-6, 0, 1.0}},
       {"sum_v ", {1e-5, 1e-4, 0, 1.0}}},
      [](Backend& b, const CheckInputs& in) {
        const SphCheckCase cs = make_sph_check_case(in, SphPressureModel::wcsph);
        const uint32_t n = cs.params.n;
        std::vector<Vec4f> acc(n), vk(n), sums(n);
        for (uint32_t i = 0; i < n; ++i) {
          const philox::Block r = philox::stream_block(in.seed, kStageStream, 2 * uint64_t(i));
          const philox::Block q = philox::stream_block(in.seed, kStageStream, 2 * uint64_t(i) + 1);
          auto s = [](uint32_t w) { return 60.0f * philox::u01(w) - 30.0f; };
          acc[i] = {s(r.w[0]), s(r.w[1]), s(r.w[2]), 0};
          vk[i] = {s(r.w[3]) / 10, s(q.w[0]) / 10, s(q.w[1]) / 10, 0};
          sums[i] = {s(q.w[2]), s(q.w[3]), s(r.w[0]), 0};
        }
        CheckOutputs out;
        for (uint32_t op = 0; op <= uint32_t(SphStageOp::drift); ++op) {
          auto x0 = b.create<Real4>(n, "check x0"), v0 = b.create<Real4>(n, "check v0"),
               vkb = b.create<Real4>(n, "check vk"), a = b.create<Real4>(n, "check a"),
               xo = b.create<Real4>(n, "check xo"), vo = b.create<Real4>(n, "check vo"),
               sx = b.create<Real4>(n, "check sx"), sv = b.create<Real4>(n, "check sv");
          auto stats = b.create<uint32_t>(kSphStatWords, "check stats");
          b.upload(x0, cs.positions);
          b.upload(v0, cs.velocities);
          b.upload(vkb, vk);
          b.upload(a, acc);
          b.upload(sx, sums);
          b.upload(sv, sums);
          b.fill(stats, 0u);
          SphIntegrateParams p;
          p.n = n;
          p.op = SphStageOp(op);
          p.dt = 2e-3;
          p.walls = true;
          p.box_min = cs.params.box_min;
          p.box_max = cs.params.box_max;
          p.restitution = 0.4;
          p.tangential_damping = 0.1;
          const bool uses_vk =
              op >= uint32_t(SphStageOp::rk4_stage2) && op <= uint32_t(SphStageOp::rk4_final);
          sph_integrate(b, p, {&x0, &v0, uses_vk ? &vkb : nullptr, &a, &xo, &vo, &sx, &sv, &stats});
          out.push_back({fmt::format("v op {}", op), {}, xyz_components(b.download(vo))});
          if (p.op != SphStageOp::kick && p.op != SphStageOp::accelerate)
            out.push_back({fmt::format("x op {}", op), {}, xyz_components(b.download(xo))});
          if (op >= uint32_t(SphStageOp::rk4_stage1) && op <= uint32_t(SphStageOp::rk4_stage3))
            out.push_back({fmt::format("sum_v op {}", op), {}, xyz_components(b.download(sv))});
        }
        return out;
      }));
  for (KernelCheck& k : dfsph_checks()) c.push_back(std::move(k));
  return c;
}

}  // namespace masav::verify
