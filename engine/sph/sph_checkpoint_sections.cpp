// The sections of an SPH checkpoint: the scene's fields (every field of SphScene: each one
// changes the run), the host's step control and the particles, written and read back.
#include "engine/sph/sph_checkpoint_sections.h"

#include <fmt/format.h>

#include <optional>
#include <type_traits>
#include <utility>

#include "engine/core/error.h"
#include "engine/sph/sph_checkpoint_codec.h"
#include "engine/sph/sph_particles.h"
#include "engine/sph/sph_presets.h"
#include "engine/sph/sph_resume_checks.h"

namespace masav {
namespace checkpoint_io {
namespace {

constexpr uint32_t kMaxPresetBytes = 256;

struct SceneWriter {
  Out& out;
  void operator()(const char*, const std::string& v) { out.string(v); }
  void operator()(const char*, uint32_t v) { out.put(v); }
  void operator()(const char*, uint64_t v) { out.put(v); }
  void operator()(const char*, double v) { out.put(v); }
  void operator()(const char*, bool v) { out.put(uint8_t(v)); }
  void operator()(const char*, const Vec3d& v) {
    out.put(v.x);
    out.put(v.y);
    out.put(v.z);
  }
  void operator()(const char*, const std::optional<double>& v) {
    out.put(uint8_t(v.has_value()));
    out.put(v.value_or(0.0));
  }
  template <class E>
  requires std::is_enum_v<E>
  void operator()(const char*, E v) { out.put(uint32_t(v)); }
};

struct SceneReader {
  In& in;
  void operator()(const char* f, std::string& v) { v = in.string(f, kMaxPresetBytes); }
  void operator()(const char* f, uint32_t& v) { v = in.get<uint32_t>(f); }
  void operator()(const char* f, uint64_t& v) { v = in.get<uint64_t>(f); }
  void operator()(const char* f, double& v) { v = in.real(f); }
  void operator()(const char* f, bool& v) { v = in.flag(f); }
  void operator()(const char* f, Vec3d& v) {
    v.x = in.real(f);
    v.y = in.real(f);
    v.z = in.real(f);
  }
  void operator()(const char* f, std::optional<double>& v) {
    const bool has = in.flag(f);
    const double x = in.real(f);
    v = has ? std::optional<double>(x) : std::nullopt;
  }
  void operator()(const char* f, SphPressureModel& v) {
    v = in.enumeration(f, SphPressureModel::dfsph);
  }
  void operator()(const char* f, SphIntegrator& v) {
    v = in.enumeration(f, SphIntegrator::leapfrog);
  }
  void operator()(const char* f, SphCflGuard& v) { v = in.enumeration(f, SphCflGuard::off); }
};

template <class S, class F>
void visit_scene(S& s, F&& f) {
  f("preset", s.preset);
  f("particles", s.particles);
  f("block.min", s.block.min);
  f("block.max", s.block.max);
  f("block.velocity", s.block.velocity);
  f("block.density_ratio", s.block.density_ratio);
  f("block.hydrostatic", s.block.hydrostatic);
  f("obstacle.enabled", s.obstacle.enabled);
  f("obstacle.min", s.obstacle.min);
  f("obstacle.max", s.obstacle.max);
  f("obstacle.mass_ratio", s.obstacle.mass_ratio);
  f("obstacle.pinned", s.obstacle.pinned);
  f("model", s.model);
  f("rest_density", s.rest_density);
  f("h_over_dx", s.h_over_dx);
  f("smoothing_radius", s.smoothing_radius);
  f("viscosity", s.viscosity);
  f("sound_speed", s.sound_speed);
  f("kp", s.kp);
  f("clamp_negative_pressure", s.clamp_negative_pressure);
  f("dfsph_density_error", s.dfsph_density_error);
  f("dfsph_divergence_error", s.dfsph_divergence_error);
  f("dfsph_max_iterations", s.dfsph_max_iterations);
  f("gravity", s.gravity);
  f("box_min", s.box_min);
  f("box_max", s.box_max);
  f("walls", s.walls);
  f("restitution", s.restitution);
  f("tangential_damping", s.tangential_damping);
  f("integrator", s.integrator);
  f("dt", s.dt);
  f("cfl_velocity", s.cfl_velocity);
  f("cfl_force", s.cfl_force);
  f("cfl_viscous", s.cfl_viscous);
  f("dt_max", s.dt_max);
  f("dt_min", s.dt_min);
  f("cfl_guard", s.cfl_guard);
  f("rk4_skin", s.rk4_skin);
  f("max_candidates", s.max_candidates);
  f("seed", s.seed);
  f("jitter", s.jitter);
}

void put_stats(Out& o, const SphStepStats& s) {
  o.put(s.max_speed);
  o.put(s.max_accel);
  o.put(s.max_drift);
  o.put(s.max_density);
  o.put(s.max_candidates);
  o.put(s.max_neighbors);
  o.put(s.outside);
}

SphStepStats get_stats(In& in, const char* field) {
  SphStepStats s;
  s.max_speed = in.real(field);
  s.max_accel = in.real(field);
  s.max_drift = in.real(field);
  s.max_density = in.real(field);
  s.max_candidates = in.get<uint32_t>(field);
  s.max_neighbors = in.get<uint32_t>(field);
  s.outside = in.get<uint32_t>(field);
  return s;
}

}  // namespace

std::vector<uint8_t> scene_bytes(const SphScene& s) {
  Out o;
  visit_scene(s, SceneWriter{o});
  return std::move(o.bytes());
}

std::vector<uint8_t> state_bytes(const SphResumeState& r) {
  Out o;
  o.put(uint64_t(r.positions.size()));
  o.put(r.time);
  o.put(r.last_dt);
  o.put(r.adaptive_dt);
  o.put(r.steps);
  o.put(r.substeps);
  o.put(r.retries);
  o.put(r.block_replays);
  put_stats(o, r.stats);
  put_stats(o, r.lag_stats);
  const SphSolveStats& ss = r.solve_stats;
  o.put(ss.steps);
  o.put(ss.density_iterations);
  o.put(ss.divergence_iterations);
  o.put(ss.unconverged);
  o.put(ss.last_density_error);
  o.put(ss.last_divergence_error);
  o.put(uint8_t(r.accel_valid));
  o.put(uint8_t(r.fields_current));
  o.put(uint8_t(r.kappa_warm));
  o.put(r.block_steps);
  o.put(uint8_t(!r.block_stats.empty()));
  if (!r.block_stats.empty()) {
    o.put(r.block_limit);
    o.array(r.block_stats);
  }
  o.put(r.watchdog.max_speed);
  o.put(r.watchdog.max_density);
  o.put(r.watchdog.energy0);
  o.put(r.next_energy_check);
  o.put(r.good_time);
  o.put(r.good_last_dt);
  o.put(r.good_steps);
  o.put(r.good_substeps);
  put_stats(o, r.good_stats);
  o.put(uint8_t(!r.kappa_density.empty()));
  return std::move(o.bytes());
}

std::vector<uint8_t> particle_bytes(const SphResumeState& r) {
  Out o;
  o.array(r.positions);
  o.array(r.velocities);
  o.array(r.accel);
  o.array(r.ids);
  o.array(r.density);
  o.array(r.pressure);
  o.array(r.kappa_density);
  o.array(r.kappa_divergence);
  o.array(r.good_positions);
  o.array(r.good_velocities);
  return std::move(o.bytes());
}

void read_sections(const std::vector<uint8_t> (&payload)[3], const std::string& path,
                   SphCheckpoint& c) {
  In scene(payload[0], path, "SCEN");
  visit_scene(c.scene, SceneReader{scene});
  scene.end();
  // The preset names the run's output files (`masav sph` NAME_STEP.vtp): only the presets' own
  // names and the API's "custom".
  bool known = c.scene.preset == "custom";
  std::string names = "custom";
  for (const SphPresetInfo& p : sph_presets()) {
    known = known || c.scene.preset == p.name;
    names += ", " + p.name;
  }
  if (!known)
    fail(path, "SCEN.preset",
         fmt::format("'{}' where one of {} was expected", c.scene.preset, names));
  uint64_t scene_total = 0;  // the particles a simulation of the scene holds
  try {
    scene_total = sph_spacing(c.scene).total();  // validates the scene
  } catch (const Error& e) {
    fail(path, "SCEN", fmt::format("{}; {}", e.problem(), e.remedy()));
  }

  In s(payload[1], path, "STAT");
  SphResumeState& r = c.state;
  const uint64_t n = s.get<uint64_t>("particles");
  // Bounded before anything is allocated: the scene's limit, and the bytes PART holds (its 10
  // arrays take at least 140 bytes per particle).
  if (n == 0 || n > kSphCheckpointMaxParticles)
    fail(path, "STAT.particles",
         fmt::format("{} where 1 to {} was expected", n, kSphCheckpointMaxParticles));
  if (n > payload[2].size() / 140)
    fail(path, "STAT.particles",
         fmt::format("{} particles need more than the {} bytes of the PART section", n,
                     payload[2].size()));
  if (c.scene.particles > n)
    fail(path, "SCEN.particles",
         fmt::format("{} fluid particles where STAT holds {} in all", c.scene.particles, n));
  // A simulation built from the scene holds exactly this many (its fluid and its obstacle).
  if (n != scene_total)
    fail(path, "STAT.particles",
         fmt::format("{} where the scene has {} ({} fluid particles and its obstacle)", n,
                     scene_total, c.scene.particles));
  r.time = s.real("time");
  r.last_dt = s.real("last_dt");
  r.adaptive_dt = s.real("adaptive_dt");
  r.steps = s.get<uint64_t>("steps");
  r.substeps = s.get<uint64_t>("substeps");
  r.retries = s.get<uint64_t>("retries");
  r.block_replays = s.get<uint64_t>("block_replays");
  r.stats = get_stats(s, "stats");
  r.lag_stats = get_stats(s, "lag_stats");
  SphSolveStats& ss = r.solve_stats;
  ss.steps = s.get<uint64_t>("solve_stats");
  ss.density_iterations = s.get<uint64_t>("solve_stats");
  ss.divergence_iterations = s.get<uint64_t>("solve_stats");
  ss.unconverged = s.get<uint64_t>("solve_stats");
  ss.last_density_error = s.real("solve_stats");
  ss.last_divergence_error = s.real("solve_stats");
  r.accel_valid = s.flag("accel_valid");
  r.fields_current = s.flag("fields_current");
  r.kappa_warm = s.flag("kappa_warm");
  r.block_steps = s.get<uint32_t>("block_steps");
  if (s.flag("block_open")) {
    r.block_limit = s.real("block_limit");
    if (!(r.block_limit > 0))
      fail(path, "STAT.block_limit",
           fmt::format("{} where a positive dt was expected", r.block_limit));
    r.block_stats = s.array<uint32_t>("block_stats", kSphStatWords);
  }
  r.watchdog.max_speed = s.real("watchdog.max_speed");
  r.watchdog.max_density = s.real("watchdog.max_density");
  r.watchdog.energy0 = s.real("watchdog.energy0");
  r.next_energy_check = s.get<uint64_t>("next_energy_check");
  r.good_time = s.real("good.time");
  r.good_last_dt = s.real("good.last_dt");
  r.good_steps = s.get<uint64_t>("good.steps");
  r.good_substeps = s.get<uint64_t>("good.substeps");
  r.good_stats = get_stats(s, "good.stats");
  const bool kappas = s.flag("dfsph kappa sums");
  s.end();
  if (kappas != (c.scene.model == SphPressureModel::dfsph))
    fail(path, "STAT.dfsph kappa sums",
         fmt::format("{} for a scene of pressure model {}", kappas ? "present" : "absent",
                     to_string(c.scene.model)));

  In p(payload[2], path, "PART");
  const uint64_t nk = kappas ? n : 0;
  r.positions = p.array<Vec4d>("positions", n);
  r.velocities = p.array<Vec4d>("velocities", n);
  r.accel = p.array<Vec4d>("accelerations", n);
  r.ids = p.array<uint32_t>("ids", n);
  r.density = p.array<double>("density", n);
  r.pressure = p.array<double>("pressure", n);
  r.kappa_density = p.array<double>("dfsph density kappa sums", nk);
  r.kappa_divergence = p.array<double>("dfsph divergence kappa sums", nk);
  r.good_positions = p.array<Vec4d>("watchdog positions", n);
  r.good_velocities = p.array<Vec4d>("watchdog velocities", n);
  p.end();
  // The checksums say the bytes are the ones written; this says they make a run of the scene.
  try {
    validate_resume_state(c.scene, r);
  } catch (const Error& e) {
    fail(path, "state", fmt::format("{}; {}", e.problem(), e.remedy()));
  }
}

}  // namespace checkpoint_io

using checkpoint_io::Out;
using checkpoint_io::SceneWriter;
using checkpoint_io::visit_scene;

std::string sph_scene_difference(const SphScene& a, const SphScene& b) {
  std::vector<std::pair<std::string, std::vector<uint8_t>>> fa;
  visit_scene(a, [&](const char* name, const auto& v) {
    Out o;
    SceneWriter{o}(name, v);
    fa.emplace_back(name, std::move(o.bytes()));
  });
  size_t i = 0;
  std::string differs;
  visit_scene(b, [&](const char* name, const auto& v) {
    Out o;
    SceneWriter{o}(name, v);
    if (differs.empty() && o.bytes() != fa[i].second) differs = name;
    ++i;
  });
  return differs;
}

}  // namespace masav
