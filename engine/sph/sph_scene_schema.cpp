#include "engine/sph/sph_scene_schema.h"

#include <cmath>

#include "engine/core/error.h"
#include "engine/sph/sph_presets.h"

namespace masav::sph {

const scene::TableSchema& sph_table() {
  static const scene::TableSchema t = [] {
    scene::TableSchema s("sph",
                         "the SPH fluid (thesis ch. 4): a preset, its fluid constants, the "
                         "integrator and time step; every key but color_by and substeps "
                         "restarts the simulation when changed");
    s.choice("preset", "water", {"explosion", "water", "dambreak", "mud", "obstacle"},
             "initial state and thesis constants: explosion (Fig. 4.10), water cube drop "
             "(Figs. 4.11-4.12), dambreak (Martin & Moyce), mud (Fig. 4.13), obstacle (§4.5.1); "
             "restarts");
    s.integer("count", 32768, 1, 16777216,
              "fluid particles (the obstacle adds its own); up to the device's largest buffer; "
              "restarts",
              "particles");
    s.choice("pressure", "wcsph", {"wcsph", "thesis", "dfsph"},
             "pressure model: wcsph (Tait, symmetric), thesis (Eq. 4.5-4.7 as printed) or "
             "dfsph (divergence-free SPH, incompressible; steps with symplectic Euler whatever "
             "the integrator); restarts");
    s.choice("integrator", "leapfrog", {"euler", "symplectic-euler", "rk4", "leapfrog"},
             "time integrator (thesis Fig. 4.2, Eq. 4.8-4.12; leapfrog: kick-drift-kick); "
             "restarts");
    s.choice("dt_mode", "cfl", {"cfl", "fixed"},
             "cfl: adaptive step from the CFL conditions; fixed: dt_s (split by the guard when "
             "over the limit); restarts");
    s.real("dt_s", 2e-4, 1e-7, 1e-2, "the fixed time step (dt_mode = fixed); restarts", "s")
        .log_scale();
    s.choice("cfl_guard", "reduce", {"reduce", "stop", "off"},
             "an unstable step: reduce (split and retry), stop (error with advice), off; "
             "restarts");
    s.integer("substeps", 10, 1, 1000,
              "simulation steps per rendered frame (changing it does not restart)", "steps");
    s.real("viscosity_scale", 1.0, 0.0, 1000.0,
           "multiplies the preset's kinematic viscosity (the thesis's nu); restarts")
        .log_scale();
    s.real("stiffness_scale", 1.0, 0.01, 100.0,
           "multiplies the pressure stiffness: wcsph c0^2 (Tait B), thesis kp; restarts")
        .log_scale();
    s.real("restitution", -1.0, -1.0, 1.0,
           "normal velocity kept at a wall bounce, 0..1; -1: the preset's value; restarts");
    s.real("gravity", 9.81, 0.0, 100.0, "downward (-y) acceleration; restarts", "m/s^2");
    s.choice("color_by", "speed", {"speed", "density", "pressure", "uniform"},
             "per-particle value shown through the colour map (obstacle particles are grey); "
             "changing it reruns nothing");
    return s;
  }();
  return t;
}

std::string preset_name(std::string_view choice) {
  return choice == "dambreak" ? std::string("dam-break") : std::string(choice);
}

bool restarts_simulation(std::string_view key) {
  return key != "color_by" && key != "substeps";
}

SphScene scene_from_params(const scene::ParamSet& p) {
  SphScene s = make_preset(preset_name(p.get_text("sph.preset")), uint32_t(p.get_int("sph.count")));
  s.model = parse_pressure_model(p.get_text("sph.pressure"), "sph.pressure");
  s.integrator = parse_integrator(p.get_text("sph.integrator"), "sph.integrator");
  if (s.model == SphPressureModel::dfsph) s.integrator = SphIntegrator::symplectic_euler;
  s.cfl_guard = parse_cfl_guard(p.get_text("sph.cfl_guard"), "sph.cfl_guard");
  if (p.get_text("sph.dt_mode") == "fixed")
    s.dt = p.get_real("sph.dt_s");
  else
    s.dt.reset();
  s.viscosity *= p.get_real("sph.viscosity_scale");
  const double stiff = p.get_real("sph.stiffness_scale");
  s.sound_speed *= std::sqrt(stiff);  // Tait B = rho0 c0^2 / 7
  s.kp *= stiff;
  if (p.get_real("sph.restitution") >= 0) s.restitution = p.get_real("sph.restitution");
  s.gravity = {0.0, -p.get_real("sph.gravity"), 0.0};
  validate(s);
  return s;
}

}  // namespace masav::sph
