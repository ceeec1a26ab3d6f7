// `masav bench sph`: SPH throughput per backend x integrator x particle count, with the stage
// breakdown (grid, density, forces, integrate) from device timestamps, and run time against
// error: integrator x dt on a dam break against RK4 at dt/16 on the CPU reference (fp64).
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>  // clock_gettime (POSIX): the calling thread's CPU time
#include <sstream>

#include "app/bench_common.h"
#include "app/vocabulary.h"
#include "engine/core/error.h"
#include "engine/cpu/cpu_backend.h"
#include "engine/sph/sph_coefficients.h"
#include "engine/sph/sph_diagnostics.h"
#include "engine/sph/sph_presets.h"
#include "engine/sph/sph_simulation.h"

namespace masav::app {

struct SphBenchOptions : BenchOptions {
  std::string counts = "32768,131072,1048576";
  std::string integrators = "euler,leapfrog,rk4";
  std::string preset = "water";
  int steps = 0;  // timed steps per run; 0: about 2M particle-steps, between 2 and 20
  bool skip_error = false;
  uint32_t error_particles = 4096;
  double error_time = 0.02;  // s of dam break for the run-time/error sweep
  uint32_t block_steps = 8;  // SphSimulation::set_block_steps of the throughput runs
};

namespace {

std::vector<std::string> split(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  std::string item;
  while (std::getline(ss, item, ','))
    if (!item.empty()) out.push_back(item);
  return out;
}

// What one step asks of the device, averaged over an unprofiled run (profiling adds a wait).
struct StepCounts {
  double launches = 0, barriers = 0, host_syncs = 0, fills = 0, device_copies = 0;
  double bytes_to_device = 0, bytes_to_host = 0;
  double async_reads = 0;   // stats read while later work kept the device busy
  double host_ms = 0;       // CPU time of the calling thread: recording, submitting, reading stats
  double graphs = 0;        // captured blocks queued as one unit (CUDA graphs, Vulkan replays)
  double graph_builds = 0;  // of them, those that built their unit (the rest reused one)
  double pipelines_built = 0;  // kernel forms compiled mid-run (DeviceCounters::pipelines_built)
};

struct Throughput {
  double step_ms = 0, wall_ms = 0;  // device time per step (sum of stages), wall time per step
  std::array<double, size_t(SphStage::count)> stage_ms{};
  StepCounts per_step;
  int steps = 0;
  uint32_t particles = 0;
  double dt = 0;
  double mean_compression = 0, max_compression = 0;  // compression max(rho/rho0 - 1, 0) at the end
};

double thread_cpu_ms() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return double(ts.tv_sec) * 1e3 + double(ts.tv_nsec) * 1e-6;
}

Throughput measure(Backend& b, const SphScene& scene, int steps, uint32_t block_steps) {
  SphSimulation sim(b, scene);
  sim.set_block_steps(block_steps);
  // Warm-up (pipelines, caches, the first adaptive steps): one whole block at least, so that the
  // timed run starts where a block of the fixed schedule does and reads its stats once a block.
  sim.run(std::max<uint64_t>(2, sim.block_steps()));
  Throughput t;
  // Wall time, counts and host time without profiling.
  b.reset_counters();
  uint64_t sub0 = sim.substeps();
  const double cpu0 = thread_cpu_ms();
  const auto t0 = std::chrono::steady_clock::now();
  sim.run(uint64_t(steps));
  const double wall =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  const double counted = double(sim.substeps() - sub0);
  const DeviceCounters& c = b.counters();
  t.per_step = {double(c.launches) / counted,       double(c.barriers) / counted,
                double(c.host_syncs) / counted,     double(c.fills) / counted,
                double(c.device_copies) / counted,  double(c.bytes_to_device) / counted,
                double(c.bytes_to_host) / counted,  double(c.async_reads) / counted,
                (thread_cpu_ms() - cpu0) / counted, double(c.graphs) / counted,
                double(c.graph_builds) / counted,   double(c.pipelines_built) / counted};
  t.wall_ms = wall / counted;
  // Device time per stage, from timestamps, in a second run.
  sim.set_profiling(true);
  sim.reset_stage_ms();
  sub0 = sim.substeps();
  sim.run(uint64_t(steps));
  t.stage_ms = sim.stage_ms();
  const double taken = double(sim.substeps() - sub0);
  for (double& s : t.stage_ms) s /= taken;
  for (double s : t.stage_ms) t.step_ms += s;
  t.steps = int(taken);
  t.particles = sim.particle_count();
  t.dt = sim.last_dt();
  const SphDiagnostics d = compute_diagnostics(sim.download(), sim);
  t.mean_compression = d.mean_compression;
  t.max_compression = d.max_compression;
  return t;
}

struct ErrorRun {
  std::string integrator;
  double dt = 0, wall_ms = 0;
  uint64_t steps = 0;
  double position_error = 0;  // RMS |x - x_ref| / h
  double velocity_error = 0;  // relative L2 of velocities
  double energy_error = 0;    // |E - E_ref| / |E_ref(0)|
  bool stable = true;
};

SphScene error_scene(const SphBenchOptions& o, SphIntegrator integ, double dt) {
  SphScene s = make_preset("dam-break", o.error_particles);
  s.integrator = integ;
  s.dt = dt;
  s.cfl_guard = SphCflGuard::off;  // measure the integrator as asked, unstable or not
  return s;
}

struct Final {
  SphState state;
  double energy0 = 0, energy = 0, wall_ms = 0;
  uint64_t steps = 0;
  bool ok = true;
};

// Runs `n` steps of s.dt.
Final run_steps(Backend& b, const SphScene& s, uint64_t n) {
  Final f;
  SphSimulation sim(b, s);
  f.energy0 = compute_diagnostics(sim.download(), sim).total();
  const auto t0 = std::chrono::steady_clock::now();
  try {
    sim.run(n);
  } catch (const Error&) {
    f.ok = false;
  }
  f.wall_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  f.steps = sim.steps();
  f.state = sim.download();
  f.energy = compute_diagnostics(f.state, sim).total();
  return f;
}

int run_sph_bench(const SphBenchOptions& o, JsonWriter& j) {
  std::vector<uint32_t> counts;
  for (const auto& c : split(o.counts)) {
    char* end = nullptr;
    const unsigned long v = std::strtoul(c.c_str(), &end, 10);
    if (!end || *end || v < 1 || v > (1ul << 28))
      throw_invalid("bench sph", "--particles", c, "comma-separated particle counts in [1, 2^28]");
    counts.push_back(uint32_t(v));
  }
  // An empty list would time nothing and still exit 0.
  if (counts.empty())
    throw_invalid("bench sph", "--particles", "''", "at least one particle count in [1, 2^28]");
  std::vector<SphIntegrator> integrators;
  for (const auto& i : split(o.integrators))
    integrators.push_back(parse_integrator(i, "--integrators"));
  if (integrators.empty())
    throw_invalid("bench sph", "--integrators", "''",
                  "at least one of euler, symplectic-euler, rk4, leapfrog");

  j.field("preset", o.preset);
  j.key("thesis_table_4_1").begin_object();  // 32,768 particles, steps per second
  j.field("note", "Quadro FX 5800 GPU / Core2 Duo P8400 CPU, 32,768 particles, frames per second");
  j.field("gpu_euler", "8.8 / 10.5 / 7.2 (water / mud / explosion)");
  j.field("gpu_rk4", "8.6 / 10.4 / 7.0");
  j.field("cpu_euler", "0.41 / 0.31 / 0.48");
  j.field("cpu_rk4", "0.25 / 0.21 / 0.35");
  j.end_object();
  j.key("throughput").begin_array();
  fmt::print(
      "bench sph: preset {}, device time per step by stage (ms, a profiled run), wall time and "
      "device work per step (an unprofiled run)\n",
      o.preset);
  fmt::print("  {:<7} {:<10} {:>9} {:>8} {:>8} {:>8} {:>9} {:>9} {:>9} {:>9} {:>12}\n", "backend",
             "integrator", "particles", "grid", "density", "forces", "integrate", "step", "wall",
             "steps/s", "Mpart-step/s");
  auto backends = open_backends(o.choice, "--particles 32768 --skip-error");
  for (auto& b : backends) {
    for (uint32_t n : counts) {
      for (SphIntegrator integ : integrators) {
        SphScene s = make_preset(engine_sph_preset(o.preset), n);
        s.integrator = integ;
        const int steps = o.steps ? o.steps : std::clamp(int(2e6 / n), 2, 20);
        auto row = [&] {
          const Throughput t = measure(*b, s, steps, o.block_steps);
          const double sps = 1000.0 / t.wall_ms;
          fmt::print(
              "  {:<7} {:<10} {:>9} {:>8.2f} {:>8.2f} {:>8.2f} {:>9.2f} {:>9.2f} {:>9.2f} "
              "{:>9.2f} {:>12.3f}\n",
              b->name(), to_string(integ), t.particles, t.stage_ms[0], t.stage_ms[1], t.stage_ms[2],
              t.stage_ms[3], t.step_ms, t.wall_ms, sps, sps * t.particles * 1e-6);
          const StepCounts& c = t.per_step;
          fmt::print(
              "  {:<7} {:<10} {:>9} per step: "
              "{:.1f} launches, {:.1f} barriers, {:.3f} host syncs, {:.3f} asynchronous reads, "
              "{:.3f} graphs ({:.3f} built), {:.1f} fills, {:.1f} device copies, "
              "{:.0f} B to device, {:.0f} B to host, {:.3f} ms host CPU, {:.3f} pipelines built; "
              "compression (rho/rho0 - 1) mean {:.2f}%, max {:.2f}% at the end\n",
              "", "", "", c.launches, c.barriers, c.host_syncs, c.async_reads, c.graphs,
              c.graph_builds, c.fills, c.device_copies, c.bytes_to_device, c.bytes_to_host,
              c.host_ms, c.pipelines_built, 100 * t.mean_compression, 100 * t.max_compression);
          begin_row(j, *b);
          j.field("integrator", to_string(integ)).field("particles", t.particles);
          j.field("timed_steps", t.steps).field("dt_s", t.dt);
          j.field("block_steps", o.block_steps);
          j.field("mean_compression", t.mean_compression)
              .field("max_compression", t.max_compression);
          j.key("stage_ms_per_step").begin_object();
          for (size_t k = 0; k < t.stage_ms.size(); ++k)
            j.field(to_string(SphStage(k)), t.stage_ms[k]);
          j.end_object();
          j.field("device_ms_per_step", t.step_ms).field("wall_ms_per_step", t.wall_ms);
          j.field("steps_per_s", sps).field("particle_steps_per_s", sps * t.particles);
          j.key("per_step").begin_object();
          j.field("launches", c.launches).field("barriers", c.barriers);
          j.field("host_syncs", c.host_syncs).field("async_reads", c.async_reads);
          j.field("fills", c.fills).field("graphs", c.graphs);
          j.field("graph_builds", c.graph_builds);
          j.field("device_copies", c.device_copies).field("bytes_to_device", c.bytes_to_device);
          j.field("bytes_to_host", c.bytes_to_host).field("host_cpu_ms", c.host_ms);
          j.field("pipelines_built", c.pipelines_built);
          j.end_object();
          j.end_object();
        };
        // A count over the device's buffers is skipped: the other rows still say something.
        run_row(fmt::format("{:<7} {:<10} {:>9}", b->name(), to_string(integ), n), row, "skipped");
      }
    }
  }
  j.end_array();

  if (!o.skip_error) {
    // Run time against error on a dam break: dt0 = the CFL limit at rest, dt0 / 2^k, against
    // RK4 at dt0 / 16 on the CPU reference.
    cpu::CpuBackend ref_backend;
    SphScene probe = error_scene(o, SphIntegrator::rk4, 1.0);
    const SphParticles lay = build_particles(probe);
    const double dt0 = 0.2 * lay.h / probe.sound_speed;
    // Every run ends at the same time, a whole number of dt0 steps (n0 dt0 = n0 2^k dt0/2^k):
    // rounding --error-time to each dt separately once ended the dt0 runs half a step early,
    // an error that swamped the integrators' own.
    const uint64_t n0 = std::max<uint64_t>(1, uint64_t(std::llround(o.error_time / dt0)));
    const double t_end = double(n0) * dt0;
    fmt::print(
        "\nrun time against error: dam break, {} particles, {:.6g} s ({} steps of dt0 = {:.3g} s); "
        "reference RK4 at dt0/16 (CPU, fp64)\n",
        o.error_particles, t_end, n0, dt0);
    const Final ref = run_steps(ref_backend, error_scene(o, SphIntegrator::rk4, dt0 / 16), 16 * n0);
    std::vector<double> ref_v;
    for (const auto& v : ref.state.velocities) ref_v.insert(ref_v.end(), {v.x, v.y, v.z});
    j.key("error_sweep").begin_object();
    j.field("scene", "dam-break").field("particles", o.error_particles);
    j.field("time_s", t_end).field("dt0_s", dt0);
    j.field("reference", "rk4 at dt0/16 on the CPU reference (fp64)");
    j.key("rows").begin_array();
    fmt::print("  {:<7} {:<10} {:>10} {:>7} {:>10} {:>12} {:>12} {:>12}\n", "backend", "integrator",
               "dt (s)", "steps", "wall (ms)", "pos err / h", "vel err", "energy err");
    for (auto& b : backends) {
      for (SphIntegrator integ : integrators) {
        for (int k = 0; k < 4; ++k) {
          const double dt = dt0 / double(1 << k);
          const Final f = run_steps(*b, error_scene(o, integ, dt), n0 << k);
          ErrorRun r;
          r.stable = f.ok;
          double sq = 0, dv = 0, vv = 0;
          for (size_t i = 0; i < f.state.positions.size(); ++i) {
            const Vec4d &x = f.state.positions[i], &y = ref.state.positions[i];
            sq += (x.x - y.x) * (x.x - y.x) + (x.y - y.y) * (x.y - y.y) + (x.z - y.z) * (x.z - y.z);
            const Vec4d &v = f.state.velocities[i], &w = ref.state.velocities[i];
            dv += (v.x - w.x) * (v.x - w.x) + (v.y - w.y) * (v.y - w.y) + (v.z - w.z) * (v.z - w.z);
            vv += w.x * w.x + w.y * w.y + w.z * w.z;
          }
          r.position_error = std::sqrt(sq / double(f.state.positions.size())) / lay.h;
          r.velocity_error = std::sqrt(dv / std::max(vv, 1e-300));
          r.energy_error = std::abs(f.energy - ref.energy) / std::abs(ref.energy0);
          if (!std::isfinite(r.position_error)) r.stable = false;
          fmt::print("  {:<7} {:<10} {:>10.3g} {:>7} {:>10.1f} {:>12.3g} {:>12.3g} {:>12.3g}{}\n",
                     b->name(), to_string(integ), dt, f.steps, f.wall_ms, r.position_error,
                     r.velocity_error, r.energy_error, r.stable ? "" : "  (unstable)");
          j.begin_object();
          j.field("backend", b->name()).field("device", b->caps().device_name);
          j.field("integrator", to_string(integ)).field("dt_s", dt).field("steps", f.steps);
          j.field("wall_ms", f.wall_ms).field("stable", r.stable);
          if (r.stable) {
            j.field("position_error_over_h", r.position_error);
            j.field("velocity_error", r.velocity_error).field("energy_error", r.energy_error);
          }
          j.end_object();
        }
      }
    }
    j.end_array().end_object();
  }
  return 0;
}

}  // namespace

void add_sph_bench(CLI::App& bench) {
  static SphBenchOptions o;
  auto* cmd = add_bench(
      bench, "sph", "SPH particle-steps/s by backend, integrator and count; run time against error",
      o, run_sph_bench);
  cmd->add_option("--particles", o.counts, "comma-separated particle counts")
      ->capture_default_str();
  add_old_option(*cmd, "--n", "--particles", o.counts);
  cmd->add_option("--integrators", o.integrators,
                  "comma-separated: euler, symplectic-euler, "
                  "rk4, leapfrog")
      ->capture_default_str();
  accept_old_values(cmd->add_option("--preset", o.preset, "scene timed"))
      ->check(CLI::IsMember(sph_preset_names()))
      ->capture_default_str();
  cmd->add_option("--steps", o.steps, "timed steps per run (0: ~2M particle-steps, 2..20)")
      ->check(CLI::Range(0, 100000));
  cmd->add_flag("--skip-error", o.skip_error, "skip the run-time/error sweep");
  add_ranged_option(*cmd, "--error-particles", o.error_particles, "particles of the error sweep",
                    64u, 1u << 20);
  add_ranged_option(*cmd, "--error-time", o.error_time, "simulated seconds of the error sweep",
                    1e-4, 10.0);
  add_ranged_option(*cmd, "--block-steps", o.block_steps,
                    "steps per stats read of the throughput runs (1: after every step)", 1u,
                    SphSimulation::kMaxBlockSteps);
  add_json_option(*cmd, o.json);
}

}  // namespace masav::app
