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
#include "engine/sph/sph_case_buffers.h"
#include "engine/sph/sph_kernel_calls.h"
#include "engine/sph/sph_particles.h"
#include "engine/util/error_metrics.h"

namespace masav::verify {
namespace {

// Philox streams of the check inputs.
constexpr uint64_t kJitterStream = 11, kVelocityStream = 12, kStageStream = 13;

struct SphCheckCase {
  std::vector<Vec4f> positions, velocities;
  SphStepParams params;
};

// side^3 particles at spacing dx = 1 cm (h = 2 dx), jittered by 0.3 dx, velocities up to
// 0.3 m/s; every 37th particle pinned, some 1000x heavier; the box's walls lie just outside the
// lattice (0.1-0.3 dx beyond its outermost jitter, as a run keeps every particle inside), so
// the outer layers see their wall images. side follows the scene's check point count, capped so the
// check stays quick on any backend.
SphCheckCase make_case(const CheckInputs& in, SphPressureModel model) {
  const uint32_t side =
      uint32_t(std::clamp(std::floor(std::cbrt(double(std::max(in.points, 1u)))), 6.0, 24.0));
  const double dx = 0.01, h = 2 * dx;
  SphCheckCase c;
  auto u = [&](uint64_t stream, uint32_t i) {
    const philox::Block b = philox::stream_block(in.seed, stream, i);
    return [b](int k) { return 2.0 * double(philox::u01(b.w[k])) - 1.0; };
  };
  for (uint32_t z = 0; z < side; ++z)
    for (uint32_t y = 0; y < side; ++y)
      for (uint32_t x = 0; x < side; ++x) {
        const uint32_t i = uint32_t(c.positions.size());
        const auto j = u(kJitterStream, i), v = u(kVelocityStream, i);
        const float inv_mass = (x + y + z) % 37 == 0 ? 0.0f : ((x * y) % 29 == 1 ? 1e-3f : 1.0f);
        c.positions.push_back({float(0.05 + (x + 0.3 * j(0)) * dx),
                               float(0.05 + (y + 0.3 * j(1)) * dx),
                               float(0.05 + (z + 0.3 * j(2)) * dx), inv_mass});
        c.velocities.push_back({float(0.3 * v(0)), float(0.3 * v(1)), float(0.3 * v(2)), 0.0f});
      }
  const uint32_t n = uint32_t(c.positions.size());
  const float cell = float(h);
  const uint32_t cells = uint32_t(std::ceil((0.1 + side * dx) / double(cell)));
  SphStepParams& p = c.params;
  p.grid = make_grid_params({0, 0, 0}, std::nextafter(cell, 1.0f), {cells, cells, cells}, n);
  p.n = n;
  p.model = model;
  p.h = h;
  p.mass = lattice_mass(1000.0, dx, h);
  p.rest_density = 1000.0;
  p.sound_speed = 15.0;
  p.kp = 5.0;
  p.viscosity = 2e-3;
  p.gravity = {0.0, -9.81, 0.0};
  p.walls = true;
  p.box_min = {0.05 - 0.4 * dx, 0.05 - 0.5 * dx, 0.05 - 0.6 * dx};
  p.box_max = {0.05 + (side - 0.4) * dx, 0.05 + (side - 0.6) * dx, 0.05 + (side - 0.5) * dx};
  return c;
}

// Outputs compared one by one, each with its tolerance; `scaled` tolerances measure errors
// relative to the reference output's RMS (times rel_floor) plus `floor_abs`.
struct OutputTolerance {
  std::string prefix;  // applies to outputs whose name starts with it
  Tolerance tol;
  bool rms_floor = false;
  double floor_abs = 0;
};

KernelCheck per_output_check(KernelId kernel, std::vector<OutputTolerance> tols,
                             std::function<CheckOutputs(Backend&, const CheckInputs&)> run) {
  KernelCheck k;
  k.kernel = kernel_name(kernel);
  k.kind = CheckKind::tolerance;
  k.run = std::move(run);
  k.compare = [tols](const CheckOutputs& got, const CheckOutputs& want, const CheckInputs&) {
    Verdict all;
    all.pass = true;
    std::string first_failure, first_metrics, described;
    for (const auto& w : want) {
      const OutputTolerance* t = nullptr;
      for (const auto& o : tols)
        if (w.name.rfind(o.prefix, 0) == 0) t = &o;
      Verdict v;
      if (!t) {
        v.metrics = "no tolerance stated";
      } else {
        Tolerance tol = t->tol;
        if (t->rms_floor) tol.rel_floor = tol.rel_floor * rms(w.reals) + t->floor_abs;
        CheckOutputs g1;
        for (const auto& g : got)
          if (g.name == w.name) g1.push_back(g);
        v = compare_tolerance(g1, {w}, tol);
        if (described.find(t->prefix + ":") == std::string::npos) {
          std::string rel =
              t->rms_floor ? fmt::format(" (relative to {:.3g} x RMS{})", t->tol.rel_floor,
                                         t->floor_abs > 0 ? fmt::format(" + {:.3g}", t->floor_abs)
                                                          : std::string())
                           : std::string();
          described += fmt::format("{}{}: {}{}", described.empty() ? "" : "; ", t->prefix,
                                   t->tol.describe(), rel);
        }
      }
      if (first_metrics.empty()) first_metrics = w.name + ": " + v.metrics, all.numbers = v.numbers;
      if (!v.pass && all.pass) first_failure = w.name + ": " + v.metrics, all.numbers = v.numbers;
      all.pass = all.pass && v.pass;
    }
    all.metrics = all.pass ? fmt::format("{} outputs within tolerance (first: {})", want.size(),
                                         first_metrics)
                           : first_failure;
    all.tolerance = described;
    return all;
  };
  return k;
}

const SphPressureModel kModels[] = {SphPressureModel::wcsph, SphPressureModel::thesis};

// A check's run over both pressure models: the case of each model sorted into its grid on the
// backend, then `body` runs the kernel and appends outputs named with the model.
template <class Body>
std::function<CheckOutputs(Backend&, const CheckInputs&)> for_each_model(Body body) {
  return [body](Backend& b, const CheckInputs& in) {
    CheckOutputs out;
    for (SphPressureModel model : kModels) {
      const SphCheckCase cs = make_case(in, model);
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
  // candidate, and over the neighbour row masks sph_density records at these positions.
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
        for (const bool masked : {false, true}) {
          sph_forces(b, cs.params,
                     {&s.sorted_pos, &s.sorted_vel, &s.density, &s.pressure, s.view(), &s.accel,
                      &s.stats, masked ? &s.neighbor_rows : nullptr});
          const auto a = b.download(s.accel);
          std::vector<double> w(a.size());
          for (size_t i = 0; i < a.size(); ++i) w[i] = a[i].w;
          const std::string variant = masked ? m + " over row masks" : m;
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
        const SphCheckCase cs = make_case(in, SphPressureModel::wcsph);
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
        for (uint32_t op = 0; op <= uint32_t(SphStageOp::kick); ++op) {
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
          if (p.op != SphStageOp::kick)
            out.push_back({fmt::format("x op {}", op), {}, xyz_components(b.download(xo))});
          if (op >= uint32_t(SphStageOp::rk4_stage1) && op <= uint32_t(SphStageOp::rk4_stage3))
            out.push_back({fmt::format("sum_v op {}", op), {}, xyz_components(b.download(sv))});
        }
        return out;
      }));
  return c;
}

}  // namespace masav::verify
