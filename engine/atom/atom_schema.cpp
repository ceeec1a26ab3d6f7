#include "engine/atom/atom_schema.h"

#include <fmt/format.h>

#include "engine/atom/orbital.h"
#include "engine/atom/scatter_threshold.h"
#include "engine/core/error.h"
#include "engine/volume/volume_render.h"

namespace masav::atom {

const scene::TableSchema& atom_table() {
  static const scene::TableSchema t = [] {
    scene::TableSchema s("atom", "the hydrogen electron cloud: which state, how many particles");
    std::vector<std::string> states = preset_names();
    states.push_back("custom");
    s.choice("state", "state1", states,
             "thesis Table 2.1 preset (state1 = 1s ... state10 = 3d m=2), or custom: n, l, m");
    s.integer("n", 1, 1, kMaxN, "custom state: principal quantum number");
    s.integer("l", 0, 0, kMaxN - 1, "custom state: angular quantum number, 0 <= l < n");
    s.integer("m", 0, -(kMaxN - 1), kMaxN - 1, "custom state: magnetic quantum number, |m| <= l");
    s.choice("orbital", "complex", {"complex", "real"},
             "complex e^{i m phi} (rotationally symmetric about z) or real cos/sin(|m| phi)");
    s.integer("count", 200000, 1, 16000000,
              "particles in the cloud (the thesis used 132K-1.1M, Table 2.3)");
    s.choice("placement", "exact", {"exact", "shells"},
             "exact: inverse-CDF sampling of |psi|^2; shells: the thesis's Algorithm 2.1");
    s.integer("seed", 1, 0, int64_t(1) << 53, "Philox key: the same seed, the same cloud");
    return s;
  }();
  return t;
}

const scene::TableSchema& nebula_table() {
  static const scene::TableSchema t = [] {
    scene::TableSchema s("nebula", "the cloud lit as a reflection nebula by the nucleus (§2.2)");
    s.real("power_lm", 250000.0, 50000.0, 500000.0,
           "source power Phi (the thesis: 50K, 250K, 500K); light is linear in it", "lm");
    s.steps(25000.0);
    s.real("exposure", 0.0, 0.0, 1e30,
           "the light (cd/a0^2: lm per steradian per a0^2 towards the viewer) at full colour is "
           "1 / exposure; 0 = the state's own fixed scale: the 90th percentile of its light at "
           "Phi = 250K lm seen from the front, the same in every view and on every backend",
           "a0^2/cd");
    s.integer("density_dims", 60, 2, 512, "density grid cells per axis (the thesis's cubes)");
    s.real("box_probability", 0.999, 0.9, 0.999999,
           "the grid's cube holds at least this much of |psi|^2");
    s.real("tau_peak", 0.5, 0.0, 100.0, "scattering depth of one cell at the state's peak density");
    s.choice("path", "exact", {"exact", "midpoint"},
             "optical path: exact voxel traversal, or midpoint steps of step_a0");
    s.real("step_a0", 0.0, 0.0, 100.0, "midpoint path step (0 = half a cell)", "a0");
    return s;
  }();
  return t;
}

const scene::TableSchema& scatter_table_schema() {
  static const scene::TableSchema t = [] {
    scene::TableSchema s("scatter",
                         "the Monte Carlo multiple-scattering table P(tau, cos theta) (§2.2.3), "
                         "cached on disk by these parameters");
    s.integer("rows", 1000, 2, 100000, "tau rows (the thesis: 1000, tau 0 .. 10)");
    s.integer("bins", 72, 2, 1024, "cos theta bins (the thesis: 72)");
    s.real("tau_step", 0.01, 1e-6, 10.0, "tau between rows (the thesis: 0.01)");
    s.real("g", 0.6, -0.99, 0.99, "Henyey-Greenstein anisotropy");
    s.real("albedo", 0.6, 0.01, 1.0, "weight kept per scattering (the thesis: 0.6)");
    s.integer("photons", 2048, 16, 1 << 20, "photons per tau row");
    // 5000: a photon's events stay within a shader invocation's loop budget (lavapipe 65,535).
    s.integer("max_scatterings", 1000, 1, 5000, "scatterings before a photon is cut");
    s.integer("seed", 1, 0, int64_t(1) << 53, "Philox key of the photons");
    return s;
  }();
  return t;
}

const scene::TableSchema& volume_table() {
  static const scene::TableSchema t = [] {
    scene::TableSchema s("volume",
                         "atom-volume: the cloud voxelized (§3.3.2) and raymarched (§3.3)");
    s.integer("dims", 60, 2, 512, "voxels per axis (the thesis: 60)");
    s.real("s", 0.6, 0.0, 1.0, "volume mix: weight of the mean light g (the thesis: s > t)");
    s.steps(0.05);
    s.real("t", 0.4, 0.0, 1.0, "volume mix: weight of the probability p");
    s.steps(0.05);
    s.text("transfer_file", "",
           "transfer function: lines 'value r g b a' ('' = the thesis's blue -> green -> red)");
    volume::add_inline_transfer_key(s);
    s.real("step_voxels", 0.5, 0.05, 4.0, "raymarch step", "voxels");
    s.choice("compositing", "front_to_back", {"front_to_back", "lerp"},
             "emission-absorption front to back, or the thesis's lerp");
    s.flag("preintegrate", false,
           "integrate the transfer function over each step (front_to_back only): a step of a "
           "voxel keeps the accuracy of a finer one");
    volume::add_clip_shade_keys(s);
    s.real("gain", 1.0, 0.0, 16.0, "multiplies the raymarched image");
    s.flag("show_particles", false, "draw the lit particles over the volume as well");
    return s;
  }();
  return t;
}

OrbitalState state_of(const scene::ParamSet& p) {
  OrbitalState s;
  const std::string& name = p.get_text("atom.state");
  if (name == "custom") {
    s = {int(p.get_int("atom.n")), int(p.get_int("atom.l")), int(p.get_int("atom.m")), false};
    validate_state(s, "atom (state = custom)");
  } else {
    s = preset_state(name);
  }
  s.real = p.get_text("atom.orbital") == "real";
  return s;
}

ScatterTableParams scatter_params_of(const scene::ParamSet& p) {
  ScatterTableParams t;
  t.rows = uint32_t(p.get_int("scatter.rows"));
  t.bins = uint32_t(p.get_int("scatter.bins"));
  t.tau_step = float(p.get_real("scatter.tau_step"));
  t.g = float(p.get_real("scatter.g"));
  t.albedo = float(p.get_real("scatter.albedo"));
  t.photons_per_row = uint32_t(p.get_int("scatter.photons"));
  t.max_scatterings = uint32_t(p.get_int("scatter.max_scatterings"));
  t.seed = uint64_t(p.get_int("scatter.seed"));
  t.weight_threshold = separated_weight_threshold(t.albedo, t.weight_threshold, t.max_scatterings);
  check_scatter_cost(t, "scatter.photons");
  return t;
}

void check_scatter_cost(const ScatterTableParams& t, std::string_view photons_field) {
  const uint64_t paths = uint64_t(t.rows) * t.photons_per_row;
  if (paths <= kMaxScatterPaths) return;
  throw_invalid("scattering table", photons_field, std::to_string(t.photons_per_row),
                fmt::format("at most {} with {} rows (rows x photons is at most 2^30 photon "
                            "paths, {:.3g} here)",
                            kMaxScatterPaths / std::max(1u, t.rows), t.rows, double(paths)));
}

AtomSceneOptions scene_options_of(const scene::ParamSet& p) {
  AtomSceneOptions o;
  o.state = state_of(p);
  o.placement =
      p.get_text("atom.placement") == "shells" ? OrbitalPlacement::shells : OrbitalPlacement::exact;
  o.particles = uint32_t(p.get_int("atom.count"));
  o.seed = uint64_t(p.get_int("atom.seed"));
  o.density_dims = uint32_t(p.get_int("nebula.density_dims"));
  o.box_probability = p.get_real("nebula.box_probability");
  o.scatter = scatter_params_of(p);
  o.source_power_lm = kReferencePowerLm;
  o.tau_peak = float(p.get_real("nebula.tau_peak"));
  o.path = p.get_text("nebula.path") == "midpoint" ? OpticalPath::midpoint : OpticalPath::exact;
  o.step_a0 = float(p.get_real("nebula.step_a0"));
  if (p.has_table("volume")) {
    o.volume_dims = uint32_t(p.get_int("volume.dims"));
    o.s = float(p.get_real("volume.s"));
    o.t = float(p.get_real("volume.t"));
  }
  o.exposure = 0;  // automatic; the light stage applies nebula.exposure when it is set
  return o;
}

}  // namespace masav::atom
