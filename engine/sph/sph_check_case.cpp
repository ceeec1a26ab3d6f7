#include "engine/sph/sph_check_case.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "engine/grid/hash_grid.h"
#include "engine/kernels/philox.h"
#include "engine/sph/sph_particles.h"
#include "engine/util/error_metrics.h"

namespace masav::verify {
namespace {

// Philox streams of the check inputs.
constexpr uint64_t kJitterStream = 11, kVelocityStream = 12;

}  // namespace

SphCheckCase make_sph_check_case(const CheckInputs& in, SphPressureModel model) {
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
  p.mass = lattice_mass(1000.0, dx, h, model != SphPressureModel::thesis);
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

}  // namespace masav::verify
