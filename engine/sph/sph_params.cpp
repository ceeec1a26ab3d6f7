#include "engine/sph/sph_params.h"

#include <fmt/format.h>

#include <cmath>

#include "engine/core/enum_names.h"
#include "engine/core/error.h"
#include "engine/kernels/dfsph_params.h"
#include "engine/kernels/kernel_checks.h"

namespace masav {
namespace {

constexpr const char* kWhere = "sph scene";

std::string vec(const Vec3d& v) {
  return fmt::format("({}, {}, {})", v.x, v.y, v.z);
}

void finite(std::string_view field, double v) {
  if (!std::isfinite(v)) throw_invalid(kWhere, field, fmt::format("{}", v), "a finite number");
}
void finite(std::string_view field, const Vec3d& v) {
  if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z))
    throw_invalid(kWhere, field, vec(v), "finite in every component");
}
void in_range(std::string_view field, double v, double lo, double hi, bool lo_open = false) {
  finite(field, v);
  if (v < lo || v > hi || (lo_open && v == lo))
    throw_invalid(kWhere, field, fmt::format("{}", v),
                  fmt::format("in {}{}, {}]", lo_open ? "(" : "[", lo, hi));
}

void check_inside(std::string_view what, const Vec3d& lo, const Vec3d& hi, const SphScene& s) {
  const double l[3] = {lo.x, lo.y, lo.z}, h[3] = {hi.x, hi.y, hi.z};
  const double bl[3] = {s.box_min.x, s.box_min.y, s.box_min.z};
  const double bh[3] = {s.box_max.x, s.box_max.y, s.box_max.z};
  for (int a = 0; a < 3; ++a)
    if (l[a] < bl[a] || h[a] > bh[a])
      throw_invalid(kWhere, "box", fmt::format("{} .. {}", vec(s.box_min), vec(s.box_max)),
                    fmt::format("large enough to hold the {} ({} .. {}): grow the box or shrink "
                                "the {}",
                                what, vec(lo), vec(hi), what));
}

}  // namespace

namespace {
const char* const kIntegrators[] = {"euler", "symplectic-euler", "rk4", "leapfrog"};
const char* const kPressureModels[] = {"wcsph", "thesis", "dfsph"};
const char* const kCflGuards[] = {"reduce", "stop", "off"};

template <class E, size_t N>
E parse(std::string_view s, std::string_view field, const char* const (&names)[N],
        const char* allowed) {
  if (auto v = enum_from_name<E>(s, names)) return *v;
  throw_invalid(kWhere, field, std::string(s), allowed);
}
}  // namespace

const char* to_string(SphIntegrator i) {
  return enum_name(i, kIntegrators);
}
const char* to_string(SphPressureModel m) {
  return enum_name(m, kPressureModels);
}
const char* to_string(SphCflGuard g) {
  return enum_name(g, kCflGuards);
}

SphIntegrator parse_integrator(std::string_view s, std::string_view field) {
  return parse<SphIntegrator>(s, field, kIntegrators, "euler, symplectic-euler, rk4 or leapfrog");
}
SphPressureModel parse_pressure_model(std::string_view s, std::string_view field) {
  return parse<SphPressureModel>(s, field, kPressureModels, "wcsph, thesis or dfsph");
}
SphCflGuard parse_cfl_guard(std::string_view s, std::string_view field) {
  return parse<SphCflGuard>(s, field, kCflGuards, "reduce, stop or off");
}

void validate(const SphScene& s) {
  if (s.particles < 1)
    throw_invalid(kWhere, "particles", "0", "at least 1 (a fluid needs particles)");
  finite("block.min", s.block.min);
  finite("block.max", s.block.max);
  finite("block.velocity", s.block.velocity);
  const double ext[3] = {s.block.max.x - s.block.min.x, s.block.max.y - s.block.min.y,
                         s.block.max.z - s.block.min.z};
  for (double e : ext)
    if (!(e > 0))
      throw_invalid(kWhere, "block", fmt::format("{} .. {}", vec(s.block.min), vec(s.block.max)),
                    "min < max on every axis");
  in_range("block.density_ratio", s.block.density_ratio, 0.5, 4.0);
  finite("box_min", s.box_min);
  finite("box_max", s.box_max);
  if (!(s.box_min.x < s.box_max.x && s.box_min.y < s.box_max.y && s.box_min.z < s.box_max.z))
    throw_invalid(kWhere, "box", fmt::format("{} .. {}", vec(s.box_min), vec(s.box_max)),
                  "min < max on every axis");
  check_inside("fluid block", s.block.min, s.block.max, s);
  if (s.obstacle.enabled) {
    finite("obstacle.min", s.obstacle.min);
    finite("obstacle.max", s.obstacle.max);
    if (!(s.obstacle.min.x < s.obstacle.max.x && s.obstacle.min.y < s.obstacle.max.y &&
          s.obstacle.min.z < s.obstacle.max.z))
      throw_invalid(kWhere, "obstacle",
                    fmt::format("{} .. {}", vec(s.obstacle.min), vec(s.obstacle.max)),
                    "min < max on every axis");
    check_inside("obstacle", s.obstacle.min, s.obstacle.max, s);
    in_range("obstacle.mass_ratio", s.obstacle.mass_ratio, 1.0, 1e12);
  }
  in_range("rest_density", s.rest_density, 0.0, 1e6, true);
  if (s.smoothing_radius) {
    const double h = *s.smoothing_radius;
    if (!std::isfinite(h) || !(h > 0))
      throw_invalid(kWhere, "smoothing_radius", fmt::format("{}", h), "finite and > 0 (m)");
  } else {
    in_range("h_over_dx", s.h_over_dx, 1.0, 5.0);
  }
  in_range("viscosity", s.viscosity, 0.0, 1e3);
  if (s.model == SphPressureModel::wcsph)
    in_range("sound_speed", s.sound_speed, 0.0, 1e5, true);
  else if (s.model == SphPressureModel::thesis)
    in_range("kp", s.kp, 0.0, 1e12);
  if (s.model == SphPressureModel::dfsph) {
    if (s.integrator != SphIntegrator::symplectic_euler)
      throw_invalid(kWhere, "integrator", to_string(s.integrator),
                    "symplectic-euler with pressure dfsph (its step is a symplectic Euler step "
                    "with a density solve before the drift and a divergence solve after it)");
    if (s.block.density_ratio != 1.0)
      throw_invalid(kWhere, "density_ratio", fmt::format("{}", s.block.density_ratio),
                    "1 with pressure dfsph (an incompressible fluid cannot start compressed: "
                    "use wcsph or thesis for the explosion)");
    in_range("dfsph_density_error", s.dfsph_density_error, 1e-7, 0.1);
    in_range("dfsph_divergence_error", s.dfsph_divergence_error, 1e-7, 0.1);
    if (s.dfsph_max_iterations < 2 || s.dfsph_max_iterations > kDfsphMaxSlots)
      throw_invalid(kWhere, "dfsph_max_iterations", std::to_string(s.dfsph_max_iterations),
                    fmt::format("in [2, {}]", kDfsphMaxSlots));
  }
  finite("gravity", s.gravity);
  in_range("restitution", s.restitution, 0.0, 1.0);
  in_range("tangential_damping", s.tangential_damping, 0.0, 1.0);
  if (s.dt) {
    const double dt = *s.dt;
    if (!std::isfinite(dt) || !(dt > 0))
      throw_invalid(kWhere, "dt", fmt::format("{}", dt), "finite and > 0 (seconds)");
    if (dt > 10.0) throw_invalid(kWhere, "dt", fmt::format("{}", dt), "at most 10 s");
  }
  in_range("cfl_velocity", s.cfl_velocity, 0.0, 1.0, true);
  in_range("cfl_force", s.cfl_force, 0.0, 1.0, true);
  in_range("cfl_viscous", s.cfl_viscous, 0.0, 1.0, true);
  in_range("dt_max", s.dt_max, 0.0, 10.0, true);
  in_range("dt_min", s.dt_min, 0.0, s.dt_max, true);
  in_range("rk4_skin", s.rk4_skin, 0.0, 2.0, true);
  // Before a device is chosen: the portable budget (each kernel checks its device's own).
  constexpr uint32_t most = max_sph_candidates(kPortableLoopBudget);
  if (s.max_candidates < 1 || s.max_candidates > most)
    throw_invalid(kWhere, "max_candidates", std::to_string(s.max_candidates),
                  fmt::format("in [1, {}] (a shader invocation runs at most {} loop iterations "
                              "on lavapipe, over {} walks)",
                              most, kPortableLoopBudget, kSphWalks));
  in_range("jitter", s.jitter, 0.0, 0.45);
}

}  // namespace masav
