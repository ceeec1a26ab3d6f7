#include "engine/sph/sph_scene_type.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "engine/core/error.h"
#include "engine/grid/hash_grid.h"
#include "engine/sph/sph_scene_schema.h"
#include "engine/sph/sph_simulation.h"

namespace masav::sph {
namespace {

using scene::ParamSet;

// Obstacle particles carry an inverse mass scale (position w) of 1/mass_ratio or 0; fluid 1.
constexpr float kObstacleBelowW = 0.5f;

class SphSceneInstance final : public scene::SceneInstance {
 public:
  SphSceneInstance(Backend& b, const ParamSet& p) : SceneInstance(b, p) {
    validate(params_);
    file_preset_ = params_.get_text("sph.preset");
    graph_.add_input("frame");
    add_parameter_inputs();
    std::vector<std::string> restart_inputs;
    for (const scene::ParamSpec& s : sph_table().params())
      if (restarts_simulation(s.key)) restart_inputs.push_back("sph." + s.key);
    auto stage = [](auto fn) { return std::make_unique<scene::LambdaStage>(fn); };
    graph_.add_stage("simulation", restart_inputs,
                     [this, stage] { return stage([this] { restart(); }); });
    graph_.add_stage("step", {"simulation", "frame"},
                     [this, stage] { return stage([this] { advance(); }); });
  }

  std::vector<std::string> targets() const override { return {"step"}; }

  std::optional<double> simulated_time_s() const override {
    if (!sim_) return 0.0;
    return sim_->time();
  }

  std::string title() const override {
    const std::string& file_title = params_.get_text("scene.title");
    if (!file_title.empty() && params_.get_text("sph.preset") == file_preset_) return file_title;
    return fmt::format("masav: SPH {}", params_.get_text("sph.preset"));
  }

  scene::SceneView view() const override {
    scene::SceneView v;
    if (!sim_) return v;
    const SphScene& s = sim_->scene();
    v.box = {{float(s.box_min.x), float(s.box_min.y), float(s.box_min.z)},
             {float(s.box_max.x), float(s.box_max.y), float(s.box_max.z)}};
    scene::PointLayer pl;
    pl.positions = &sim_->positions();
    pl.count = sim_->particle_count();
    pl.version = graph_.version("step");
    pl.marker_below_w = kObstacleBelowW;
    // Colour ranges from the scene's physics: the free-fall speed over the box height, the
    // hydrostatic pressure at its floor, and the rest density with free-surface deficit.
    const double height = s.box_max.y - s.box_min.y;
    const double g = std::abs(s.gravity.y);
    const std::string& by = params_.get_text("sph.color_by");
    if (by == "speed") {
      pl.from = scene::PointLayer::ScalarFrom::vector_length;
      pl.scalar = &sim_->velocities().impl();
      pl.scalar_hi = float(g > 0 ? std::sqrt(2.0 * g * height) : 1.0);
      pl.scalar_name = "speed (m/s)";
      pl.scalar_key = "speed";
    } else if (by == "density") {
      pl.from = scene::PointLayer::ScalarFrom::buffer;
      pl.scalar = &sim_->density().impl();
      pl.scalar_lo = float(0.8 * s.rest_density);
      pl.scalar_hi = float(1.1 * s.rest_density);
      pl.scalar_name = "density (kg/m^3)";
      pl.scalar_key = "density";
    } else if (by == "pressure") {
      pl.from = scene::PointLayer::ScalarFrom::buffer;
      pl.scalar = &sim_->pressure().impl();
      pl.scalar_hi = float(s.rest_density * std::max(g, 1.0) * height);
      pl.scalar_name = "pressure (Pa)";
      pl.scalar_key = "pressure";
    }
    v.points = pl;
    return v;
  }

  // For tests and tools: the driver (null before the first update).
  const SphSimulation* simulation() const { return sim_.get(); }

 protected:
  void on_clock(const scene::FrameClock& clock) override {
    // The first frame shows the initial state; each later frame advances the simulation unless
    // the clock is paused (step_once advances one frame while paused).
    const bool advanced = seen_frame_ && clock.frame != last_frame_;
    seen_frame_ = true;
    last_frame_ = clock.frame;
    if ((advanced && !clock.paused) || clock.step_once) {
      step_due_ = true;
      graph_.touch("frame");
    }
  }

  void validate(const ParamSet& p) const override {
    const SphScene s = scene_from_params(p);
    const uint64_t limit = backend_.caps().max_buffer_bytes;
    const uint64_t bytes = 4 * uint64_t(backend_.real_bytes());  // one Real4 per particle
    if (limit != 0 && uint64_t(s.particles) * bytes > limit)
      throw_invalid(backend_.name(), "sph.count", std::to_string(s.particles),
                    fmt::format("at most {} on {} ({} MiB per buffer)", limit / bytes,
                                backend_.caps().device_name, limit >> 20));
  }

 private:
  void restart() {
    sim_.reset();  // free the old buffers first
    // A frame that advanced together with the restart still steps (the demo's `step` right
    // after an integrator change): step_due_ stays as on_clock left it.
    sim_ = std::make_unique<SphSimulation>(backend_, scene_from_params(params_));
  }

  void advance() {
    if (!step_due_) return;  // re-run after a restart: shows the new initial state
    step_due_ = false;
    sim_->run(uint64_t(params_.get_int("sph.substeps")));
  }

  std::unique_ptr<SphSimulation> sim_;
  std::string file_preset_;  // the preset the scene was created with (see title())
  bool step_due_ = false, seen_frame_ = false;
  uint64_t last_frame_ = 0;
};

// The support radius build_particles() gives the scene, without placing its particles (the
// cross-check runs before the scene exists, possibly for millions of particles).
double support_radius(const SphScene& s) {
  if (s.smoothing_radius) return *s.smoothing_radius;
  const Vec3d e{s.block.max.x - s.block.min.x, s.block.max.y - s.block.min.y,
                s.block.max.z - s.block.min.z};
  const double placed = std::cbrt(e.x * e.y * e.z / double(s.particles));
  return s.h_over_dx * placed * std::cbrt(s.block.density_ratio);
}

GridParams check_grid(const ParamSet& p, uint32_t points) {
  const SphScene s = scene_from_params(p);
  const double h = support_radius(s);
  const Vec3d ext{s.box_max.x - s.box_min.x, s.box_max.y - s.box_min.y, s.box_max.z - s.box_min.z};
  auto cells = [&](double e) { return uint32_t(std::clamp(std::ceil(e / h), 1.0, 256.0)); };
  const UVec3 dims{cells(ext.x), cells(ext.y), cells(ext.z)};
  const float cell = float(std::max({ext.x / dims.x, ext.y / dims.y, ext.z / dims.z}));
  return make_grid_params({float(s.box_min.x), float(s.box_min.y), float(s.box_min.z)}, cell, dims,
                          points);
}

}  // namespace

const SphSimulation* simulation_of(const scene::SceneInstance& s) {
  const auto* sph = dynamic_cast<const SphSceneInstance*>(&s);
  return sph ? sph->simulation() : nullptr;
}

scene::SceneType sph_scene_type() {
  scene::SceneType t;
  t.name = "sph";
  t.help = "SPH fluid (thesis ch. 4): explosion, water drop, dam break, mud, obstacle presets";
  t.tables = {&sph_table()};
  t.kernels = [](const ParamSet& p) {
    std::vector<KernelId> k{
        KernelId::grid_assign_count,  KernelId::grid_cell_offsets, KernelId::grid_scatter_cells,
        KernelId::grid_rank_and_move, KernelId::gather,            KernelId::sph_density,
        KernelId::sph_forces,         KernelId::sph_integrate};
    if (p.get_text("sph.pressure") == "dfsph")  // only the dfsph model runs its solves
      k.insert(k.end(), {KernelId::dfsph_factor, KernelId::dfsph_rate, KernelId::dfsph_correct});
    return k;
  };
  t.check_inputs = [](const ParamSet& p) {
    scene::CheckInputs c;
    c.points = uint32_t(std::min(p.get_int("sph.count"), p.get_int("verify.max_points")));
    c.seed = 1;
    c.grid = check_grid(p, c.points);
    return c;
  };
  t.make = [](Backend& b, const ParamSet& p,
              const scene::SceneHost&) -> std::unique_ptr<scene::SceneInstance> {
    return std::make_unique<SphSceneInstance>(b, p);
  };
  return t;
}

}  // namespace masav::sph
