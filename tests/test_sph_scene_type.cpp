// The `sph` scene type on the CPU reference: the frame clock steps the simulation (substeps per
// frame, pause, step_once); colour-by, camera and render changes rerun nothing; the count, the
// preset and the integrator restart it; the schema rejects bad values naming the key; the
// cross-check covers the SPH kernels; every scenes/sph_*.toml loads.
#include <doctest/doctest.h>

#include <filesystem>

#include "engine/core/error.h"
#include "engine/cpu/cpu_backend.h"
#include "engine/scene/scene.h"
#include "engine/sph/sph_presets.h"
#include "engine/sph/sph_scene_type.h"
#include "engine/sph/sph_simulation.h"
#include "engine/verify/cross_check.h"
#include "registry/check_catalog.h"
#include "registry/scene_catalog.h"
#include "registry/scene_file.h"

using namespace masav;
using namespace masav::scene;

namespace {

using Names = std::vector<std::string>;

ParamSet small_sph(int64_t count) {
  ParamSet p = default_params(find_scene_type("sph"));
  p.set("sph.count", count);
  p.set("sph.substeps", int64_t(2));
  return p;
}

}  // namespace

TEST_CASE("the sph scene steps with the frame clock and reruns nothing for colour or view") {
  cpu::CpuBackend cpu(2);
  auto s = find_scene_type("sph").create(cpu, small_sph(800));
  FrameClock clock;
  // Frame 0 shows the initial state: the simulation is built, nothing stepped.
  CHECK(s->update(clock).ran == Names{"simulation", "step"});
  const SphSimulation* sim = sph::simulation_of(*s);
  REQUIRE(sim != nullptr);
  CHECK(sim->steps() == 0);
  // Each new frame: substeps steps, never a rebuild.
  clock.frame = 1;
  CHECK(s->update(clock).ran == Names{"step"});
  CHECK(sim->steps() == 2);
  CHECK(s->update(clock).ran.empty());  // the same frame again
  // Colour-by, camera and render changes: no stage runs, the simulation does not step, and the
  // point layer switches to the new per-particle buffer.
  s->set("sph.color_by", std::string("density"));
  s->set("camera.view", std::string("front"));
  s->set("camera.yaw_deg", 10.0);
  s->set("render.colormap", std::string("inferno"));
  s->set("render.point_size", 5.0);
  const UpdateReport r = s->update(clock);
  CHECK(r.ran.empty());
  CHECK(r.skipped == Names{"simulation", "step"});
  CHECK(sim->steps() == 2);
  CHECK(s->graph().counters("simulation").runs == 1);
  REQUIRE(s->view().points.has_value());
  CHECK(s->view().points->from == PointLayer::ScalarFrom::buffer);
  CHECK(s->view().points->scalar == &sim->density().impl());
  s->set("sph.color_by", std::string("speed"));
  CHECK(s->update(clock).ran.empty());
  CHECK(s->view().points->from == PointLayer::ScalarFrom::vector_length);
  CHECK(s->view().points->scalar == &sim->velocities().impl());
  CHECK(s->view().points->positions == &sim->positions());
  CHECK(s->view().points->marker_below_w.has_value());
  // Paused: frames pass, nothing steps; step_once advances one frame's substeps.
  clock.paused = true;
  for (uint64_t f = 2; f < 5; ++f) {
    clock.frame = f;
    CHECK(s->update(clock).ran.empty());
  }
  CHECK(sim->steps() == 2);
  clock.step_once = true;
  CHECK(s->update(clock).ran == Names{"step"});
  clock.step_once = false;
  CHECK(sim->steps() == 4);
  // Substeps apply from the next frame without a restart.
  s->set("sph.substeps", int64_t(3));
  clock.paused = false;
  clock.frame = 5;
  CHECK(s->update(clock).ran == Names{"step"});
  CHECK(sph::simulation_of(*s) == sim);
  CHECK(sim->steps() == 7);
  const uint64_t step_runs = s->graph().counters("step").runs;
  CHECK(step_runs == 4);  // frames 0, 1, the step_once and frame 5

  // The particle count restarts the simulation from the preset's initial state.
  s->set("sph.count", int64_t(1000));
  CHECK(s->update(clock).ran == Names{"simulation", "step"});
  sim = sph::simulation_of(*s);
  CHECK(sim->particle_count() == 1000);
  CHECK(sim->steps() == 0);
  CHECK(s->graph().counters("simulation").runs == 2);
  // So do the integrator and the preset.
  s->set("sph.integrator", std::string("rk4"));
  CHECK(s->update(clock).ran == Names{"simulation", "step"});
  sim = sph::simulation_of(*s);
  CHECK(sim->scene().integrator == SphIntegrator::rk4);
  s->set("sph.preset", std::string("obstacle"));
  CHECK(s->update(clock).ran == Names{"simulation", "step"});
  sim = sph::simulation_of(*s);
  CHECK(sim->layout().obstacle > 0);
  CHECK(sim->particle_count() == 1000 + sim->layout().obstacle);
  CHECK(s->graph().counters("simulation").runs == 4);
  // A restart in the same update as a new frame steps the new simulation (the demo's `step`
  // right after an integrator change).
  s->set("sph.integrator", std::string("leapfrog"));
  clock.frame = 6;
  CHECK(s->update(clock).ran == Names{"simulation", "step"});
  CHECK(sph::simulation_of(*s)->steps() == 3);
}

TEST_CASE("the sph scene reports its simulated time, not the frame clock, and titles its preset") {
  cpu::CpuBackend cpu(2);
  ParamSet p = small_sph(800);
  p.set("scene.title", std::string("masav: SPH dam break"));
  p.set("sph.preset", std::string("dambreak"));
  auto s = find_scene_type("sph").create(cpu, p);
  FrameClock clock;
  CHECK(*s->simulated_time_s() == 0.0);
  for (uint64_t f = 0; f <= 5; ++f) {
    clock.frame = f;
    clock.time_s = double(f) / 30.0;
    s->update(clock);
  }
  const SphSimulation* sim = sph::simulation_of(*s);
  REQUIRE(sim != nullptr);
  CHECK(sim->steps() == 10);
  REQUIRE(s->simulated_time_s().has_value());
  CHECK(*s->simulated_time_s() == sim->time());
  CHECK(*s->simulated_time_s() > 0);
  // Two adaptive steps a frame cover far less than the frame clock's 1/30 s.
  CHECK(*s->simulated_time_s() < clock.time_s);
  CHECK(s->title() == "masav: SPH dam break");
  s->set("sph.preset", std::string("water"));
  CHECK(s->title() == "masav: SPH water");
  s->set("sph.preset", std::string("dambreak"));
  CHECK(s->title() == "masav: SPH dam break");
}

TEST_CASE("the sph scene maps its table onto the preset and rejects bad values by key") {
  cpu::CpuBackend cpu(1);
  ParamSet p = small_sph(500);
  p.set("sph.preset", std::string("dambreak"));
  p.set("sph.viscosity_scale", 2.0);
  p.set("sph.stiffness_scale", 4.0);
  p.set("sph.restitution", 0.7);
  p.set("sph.gravity", 5.0);
  p.set("sph.dt_mode", std::string("fixed"));
  p.set("sph.dt_s", 1e-4);
  p.set("sph.pressure", std::string("thesis"));
  auto s = find_scene_type("sph").create(cpu, p);
  FrameClock clock;
  s->update(clock);
  const SphScene& sc = sph::simulation_of(*s)->scene();
  const SphScene base = make_preset("dam-break", 500);
  CHECK(sc.preset == "dam-break");
  CHECK(sc.viscosity == doctest::Approx(2.0 * base.viscosity));
  CHECK(sc.sound_speed == doctest::Approx(2.0 * base.sound_speed));
  CHECK(sc.kp == doctest::Approx(4.0 * base.kp));
  CHECK(sc.restitution == 0.7);
  CHECK(sc.gravity.y == -5.0);
  CHECK(sc.model == SphPressureModel::thesis);
  REQUIRE(sc.dt.has_value());
  CHECK(*sc.dt == 1e-4);
  // The box of the view is the preset's.
  CHECK(s->view().box.hi.x == doctest::Approx(5 * 0.146));

  auto error_of = [&](const char* key, ParamValue v) {
    try {
      s->set(key, v);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("(no error)");
  };
  CHECK(error_of("sph.count", int64_t(0)).find("sph.count = 0") != std::string::npos);
  CHECK(error_of("sph.preset", std::string("lava")).find("explosion, water, dambreak") !=
        std::string::npos);
  CHECK(error_of("sph.dt_s", 1.0).find("sph.dt_s") != std::string::npos);
  CHECK(error_of("sph.integrator", std::string("rk5")).find("sph.integrator") != std::string::npos);
  CHECK(error_of("sph.substeps", int64_t(0)).find("sph.substeps") != std::string::npos);
  CHECK(error_of("sph.colour", std::string("x")).find("color_by") != std::string::npos);
  // A rejected value leaves the old one.
  CHECK(s->params().get_int("sph.count") == 500);
}

TEST_CASE("the SPH scenes load, and the cross-check covers the SPH kernels") {
  const std::filesystem::path dir = std::filesystem::path(MASAV_SOURCE_DIR) / "scenes";
  for (const char* name :
       {"sph_explosion", "sph_water", "sph_dambreak", "sph_mud", "sph_obstacle"}) {
    CAPTURE(name);
    const SceneFile f = load_scene_file((dir / (std::string(name) + ".toml")).string());
    CHECK(f.type == "sph");
    CHECK(f.params.get_text("camera.up") == "y");
  }
  cpu::CpuBackend a(2), b(1);
  ParamSet p = small_sph(3000);
  p.set("verify.max_points", int64_t(1000));
  const verify::CrossCheckReport r = verify::cross_check_scene(a, b, p);
  INFO(verify::format_report(r));
  CHECK(r.pass());
  Names kernels;
  for (const auto& row : r.rows) kernels.push_back(row.kernel);
  CHECK(kernels == Names{"grid_assign_count", "grid_cell_offsets", "grid_scatter_cells",
                         "grid_rank_and_move", "gather", "sph_density", "sph_forces",
                         "sph_integrate"});
  // A perturbed SPH kernel is caught.
  for (const char* kernel : {"sph_density", "sph_forces", "sph_integrate"}) {
    CAPTURE(kernel);
    const verify::CrossCheckReport bad = verify::cross_check_scene(a, b, p, find_kernel(kernel));
    CHECK(bad.failures() == 1);
  }
}
