// `masav sph`: runs an SPH preset headless on one backend, with per-step diagnostics (CSV) and
// particle snapshots (VTK .vtp) for ParaView. Every option is validated; an unstable run stops
// with the step, the particle and advice, and still writes the last good state.
//
// Started by mpirun on several ranks, the ranks share the simulation (engine/sph/sph_ranks.h):
// rank 0 prints, writes the CSV and the checkpoints (of the whole state, which a restart reads on
// any number of ranks); a snapshot is one .vtp piece per rank and rank 0's .pvtp index. Every
// rank takes part in each gather.
#include <fmt/format.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <limits>
#include <optional>
#include <span>

#include "app/commands.h"
#include "app/host_environment.h"
#include "app/interrupt.h"
#include "app/mpi_comm.h"
#include "app/number_checks.h"
#include "app/scene_options.h"
#include "app/vocabulary.h"
#include "engine/core/error.h"
#include "engine/sph/sph_checkpoint.h"
#include "engine/sph/sph_presets.h"
#include "engine/sph/sph_run.h"
#include "engine/sph/sph_simulation.h"
#include "registry/backends.h"

namespace masav::app {
namespace {

struct SphOptions {
  BackendChoice choice;
  std::string preset = "water";
  uint32_t particles = 32768;
  uint64_t steps = 100;
  double time = 0;  // s; > 0: run until this time instead of a step count
  std::string integrator, pressure, cfl_guard;
  std::optional<double> dt, viscosity, sound_speed, max_compression, kp, smoothing_radius,
      restitution;
  uint64_t vtp_every = 0, diag_every = 1;
  std::string csv, out;
  uint64_t seed = 1;
  uint32_t block_steps = 8;
  bool quiet = false;
  bool overwrite = false;
  uint64_t checkpoint_every = 0;  // 0: only on an interrupt and at the end (with a directory)
  std::string checkpoint_dir, restart;
};

// The options that shape the trajectory: a restart takes them from its checkpoint.
constexpr const char* kSceneFlags[] = {"--preset",          "--particles", "-n",
                                       "--integrator",      "--pressure",  "--dt",
                                       "--cfl-guard",       "--viscosity", "--sound-speed",
                                       "--max-compression", "--kp",        "--smoothing-radius",
                                       "--restitution",     "--seed",      "--block-steps"};
CLI::App* g_sph_command = nullptr;


// --out, where the .vtp files go: out/sph unless given.
std::string out_dir(const SphOptions& o) {
  return o.out.empty() ? "out/sph" : o.out;
}

SphScene scene_from(const SphOptions& o) {
  SphScene s = make_preset(engine_sph_preset(o.preset), o.particles);
  if (!o.integrator.empty()) s.integrator = parse_integrator(o.integrator, "--integrator");
  if (!o.pressure.empty()) s.model = parse_pressure_model(o.pressure, "--pressure");
  // dfsph's step is its own (a symplectic Euler step with its two solves).
  if (s.model == SphPressureModel::dfsph && o.integrator.empty())
    s.integrator = SphIntegrator::symplectic_euler;
  // Each pressure model reads one constant (dfsph neither); another one given would be silently
  // ignored.
  const bool dfsph = s.model == SphPressureModel::dfsph;
  // --max-compression sets c0, so it goes where --sound-speed goes.
  const bool c0_given = o.sound_speed || o.max_compression;
  const char* c0_flag = o.sound_speed ? "--sound-speed" : "--max-compression";
  if (dfsph && (o.kp || c0_given))
    throw Error("", o.kp ? "--kp" : c0_flag,
                fmt::format("{} conflicts with the dfsph pressure model, which solves for its "
                            "pressure instead",
                            o.kp ? "--kp" : c0_flag),
                "drop it, or use --pressure wcsph (--sound-speed, --max-compression) or thesis "
                "(--kp)");
  const bool wcsph = s.model == SphPressureModel::wcsph;
  if (wcsph ? bool(o.kp) : c0_given)
    throw Error("", wcsph ? "--kp" : c0_flag,
                fmt::format("{} conflicts with the {} pressure model (--pressure{}), which does "
                            "not read it",
                            wcsph ? "--kp" : c0_flag, to_string(s.model),
                            o.pressure.empty() ? fmt::format(" of the preset {}", o.preset)
                                               : " " + o.pressure),
                wcsph ? "drop --kp, or use --pressure thesis"
                      : fmt::format("drop {}, or use --pressure wcsph", c0_flag));
  if (!o.cfl_guard.empty()) s.cfl_guard = parse_cfl_guard(o.cfl_guard, "--cfl-guard");
  if (o.dt) s.dt = *o.dt;
  if (o.viscosity) s.viscosity = *o.viscosity;
  if (o.sound_speed) s.sound_speed = *o.sound_speed;
  if (o.max_compression) set_max_compression(s, *o.max_compression, "--max-compression");
  if (o.kp) s.kp = *o.kp;
  if (o.smoothing_radius) s.smoothing_radius = *o.smoothing_radius;
  if (o.restitution) s.restitution = *o.restitution;
  // The presets place their particles on a lattice; a seed would change nothing.
  if (g_sph_command && g_sph_command->count("--seed") > 0 && s.jitter == 0)
    throw Error("", "--seed",
                fmt::format("--seed changes nothing: the preset {} places its particles on a "
                            "lattice without jitter",
                            o.preset),
                "drop --seed");
  s.seed = o.seed;
  return s;
}



// --restart with an option that would change the trajectory: refused, naming it.
void check_restart_flags(const SphOptions& o) {
  if (o.restart.empty() || !g_sph_command) return;
  for (const char* flag : kSceneFlags)
    if (g_sph_command->count(flag) > 0)
      throw Error("", "--restart",
                  fmt::format("{} conflicts with --restart: the scene and its time stepping come "
                              "from the checkpoint",
                              flag),
                  fmt::format("drop {}; with --restart give only --steps (further steps), --time "
                              "(the end time), outputs and checkpoint options",
                              flag));
}

// Each rank's share and what its exchanges cost (the counters of engine/sph/sph_ranks.h) over
// the run's steps (`before`: the counters when they started, after the set-up's first rebuild),
// printed by rank 0: the communication figures of a run on several ranks. `seconds`: the run's
// wall time, `steps` the steps it took; what the exchanges and reductions did not take is the
// rank's compute.
void print_rank_table(SphSimulation& sim, const SphRankCounters& before, bool lead, double seconds,
                      uint64_t steps) {
  SphRanks& ranks = *sim.ranks();
  struct Row {
    uint64_t own, halo, capacity, rebuilds, migrated, bytes;
    double exchange, mpi, reduce, wall;
  };
  const SphRankLayout& l = ranks.staged();
  SphRankCounters c = ranks.counters();
  c.rebuilds -= before.rebuilds;
  c.migrated -= before.migrated;
  c.bytes_sent -= before.bytes_sent;
  c.exchange_seconds -= before.exchange_seconds;
  c.mpi_seconds -= before.mpi_seconds;
  c.reduce_seconds -= before.reduce_seconds;
  const Row mine{l.own,        l.local - l.own,    sim.capacity(), c.rebuilds,       c.migrated,
                 c.bytes_sent, c.exchange_seconds, c.mpi_seconds,  c.reduce_seconds, seconds};
  Bytes bytes;
  append_bytes(bytes, std::span<const Row>(&mine, 1));
  const Bytes all = ranks.gather(bytes);
  if (!lead) return;
  fmt::print(
      "ranks: {} (cells split along x; {} re-balances; {} steps, {} grid rebuilds; exchanges "
      "{})\n",
      ranks.ranks(), c.rebalances, steps, c.rebuilds, exchange_path());
  fmt::print(
      "  rank  own particles  halo particles  halo/own  buffers for  migrated/rebuild"
      "  KiB sent/step  exchange s  in MPI s  reduce s  compute s\n");
  for (size_t r = 0; r * sizeof(Row) < all.size(); ++r) {
    Row w;
    std::memcpy(&w, all.data() + r * sizeof(Row), sizeof w);
    const double per = double(std::max<uint64_t>(w.rebuilds, 1));
    fmt::print(
        "  {:>4}  {:>13}  {:>14}  {:>7.1f}%  {:>11}  {:>16.1f}  {:>13.1f}  {:>10.3f}  {:>8.3f}"
        "  {:>8.3f}  {:>9.3f}\n",
        r, w.own, w.halo, w.own ? 100.0 * double(w.halo) / double(w.own) : 0.0, w.capacity,
        double(w.migrated) / per, double(w.bytes) / double(std::max<uint64_t>(steps, 1)) / 1024.0,
        w.exchange, w.mpi, w.reduce, std::max(0.0, w.wall - w.exchange - w.reduce));
  }
}

// Ranks on one machine share its GPUs: without --device, a rank takes device (local rank mod the
// backend's devices), so `mpirun -np 8` on an 8-GPU node puts one rank on each.
std::string rank_device(const BackendChoice& c, const SphComm* comm) {
  if (!comm || !c.device.empty()) return c.device;
  const int local = local_rank();
  const HostRequest request(host_environment());
  const std::string name = c.backend == "auto" ? auto_backend_name(request.get()) : c.backend;
  if (local < 0 || name == "cpu") return c.device;
  for (const BackendStatus& s : list_backends(request.get()))
    if (s.name == name && s.devices.size() > 1)
      return std::to_string(size_t(local) % s.devices.size());
  return c.device;
}

// The run's first line: the scene, the particles, the model and the device.
void print_header(SphSimulation& sim, const SphOptions& o, const SphComm* comm) {
  const SphParticles& lay = sim.layout();
  const SphScene& scene = sim.scene();
  fmt::print(
      "sph {}: {} particles ({} fluid, {} obstacle), dx {:.4g} m, h {:.4g} m, {} / {}, "
      "{} on {}{}\n",
      o.preset, sim.particle_count(), lay.fluid, lay.obstacle, lay.dx, lay.h,
      to_string(scene.model), to_string(scene.integrator),
      scene.dt ? fmt::format("dt {:.3g} s", *scene.dt) : std::string("adaptive dt"),
      sim.backend().caps().device_name, comm ? fmt::format(" x {} ranks", comm->size()) : "");
}

// What the run writes, from the options (the snapshots' directory out/sph unless given).
SphRunOptions run_options(const SphOptions& o) {
  SphRunOptions r;
  r.steps = o.steps;
  r.t_end = o.time;
  r.csv = o.csv;
  r.diag_every = o.diag_every;
  r.out_dir = !o.out.empty() || o.vtp_every ? out_dir(o) : "";
  r.name = o.preset;
  r.vtp_every = o.vtp_every;
  r.checkpoint_dir = o.checkpoint_dir;
  r.checkpoint_every = o.checkpoint_every;
  r.progress_every = o.quiet ? 0 : 100;
  r.overwrite = o.overwrite;
  r.manifest = {{"command", "sph"}, {"preset", o.preset}};
  if (!o.restart.empty()) r.manifest.emplace_back("restart", o.restart);
  return r;
}

// Whether any rank was interrupted, decided once for every rank. The run's polls stop the ranks
// together, but a signal that lands during the last block (or after it) is seen by no poll: on
// rank 0 its own flag used to make the run "interrupted", on another rank it was lost and the
// run exited 0. One more reduction here makes a signal on any rank count as one on rank 0; every
// rank reaches it (none is left inside a collective when no error stopped the run).
bool any_rank_interrupted(const SphRunResult& r, SphComm* comm) {
  uint32_t flag = r.interrupted || interrupted() ? 1u : 0u;
  if (comm) comm->max(std::span<uint32_t>(&flag, 1));
  return flag != 0;
}

// The run's end: the failure and where its last good state went, the rates, dfsph's solves.
// `stopped`: any_rank_interrupted. Returns the exit status.
int report(const SphRunResult& r, SphSimulation& sim, const SphOptions& o, bool stopped) {
  if (r.error) {
    fmt::print(stderr, "masav: error: {}\n", *r.error);
    if (!r.last_good.empty())
      fmt::print(stderr, "masav: the last good state (step {}) is in {}\n", sim.steps(),
                 r.last_good);
    else if (r.last_good_skipped)
      fmt::print(stderr,
                 "masav: on several ranks the last good state is written only after the "
                 "simulation's own checks fail (this error may have stopped one rank alone)\n");
    else
      fmt::print(stderr,
                 "masav: the last good state (step {}) was not written: give --out DIR to have "
                 "it written there as a .vtp\n",
                 sim.steps());
  } else if (!r.final_checkpoint.empty()) {
    fmt::print("checkpoint {}: step {}, t = {:.6g} s\n", r.final_checkpoint, sim.steps(),
               sim.time());
  }
  if (!o.csv.empty()) fmt::print("wrote {} ({} rows)\n", o.csv, r.csv_rows);
  fmt::print(
      "{} steps ({} integrator steps, {} retried) to t = {:.5g} s in {:.2f} s: {:.1f} "
      "steps/s, {:.3g} M particle-steps/s\n",
      sim.steps(), sim.substeps(), sim.retries(), sim.time(), r.wall_s,
      double(r.steps) / r.wall_s, double(r.substeps) * sim.particle_count() / r.wall_s * 1e-6);
  if (const SphSolveStats& ss = sim.solve_stats(); ss.steps > 0)
    fmt::print(
        "dfsph: {:.2f} density and {:.2f} divergence iterations per step ({:.2f} residual reads), "
        "last mean residuals {:.3g}% and {:.3g}%, {} solves stopped at the iteration limit\n",
        double(ss.density_iterations) / double(ss.steps),
        double(ss.divergence_iterations) / double(ss.steps),
        double(sim.dfsph_residual_reads()) / double(ss.steps), 100 * ss.last_density_error,
        100 * ss.last_divergence_error, ss.unconverged);
  if (r.error) return 1;
  if (stopped) {
    fmt::print(stderr, "masav: interrupted after step {}; every row and file written is complete\n",
               sim.steps());
    return 130;
  }
  return 0;
}

int run_sph(const SphOptions& given) {
  SphOptions o = given;  // a restart takes the preset's name (for file names) from its scene
  check_restart_flags(o);
  if (g_sph_command && g_sph_command->count("--restart") > 0 && o.restart.empty())
    throw Error("", "--restart", "--restart was given an empty directory",
                "give the --checkpoint-dir of the run to resume");
  std::optional<SphCheckpoint> resumed;
  const std::string restart_file = SphRun::checkpoint_path(o.restart);
  if (!o.restart.empty()) {
    resumed = read_sph_checkpoint(restart_file);
    o.preset = resumed->scene.preset;  // the command line's name of it, where it has one
    for (const std::string& name : sph_preset_names())
      if (engine_sph_preset(name) == resumed->scene.preset) o.preset = name;
  }
  const SphScene scene = resumed ? resumed->scene : scene_from(o);
  SphComm* comm = world_comm();
  const bool lead = !comm || comm->rank() == 0;  // prints and writes
  if (!lead) o.quiet = true;
  validate(scene);  // every check of the scene before any output is opened
  SphRun run(run_options(o), comm);  // outputs held before any work: a bad path fails at once
  install_interrupt_handler();
  auto backend = open_backend(o.choice, o.choice.backend, rank_device(o.choice, comm));
  SphSimulation sim(*backend, scene, comm);
  sim.set_block_steps(o.block_steps);
  if (resumed) {
    restore_sph_checkpoint(sim, *resumed, restart_file);
    if (lead)
      fmt::print("resumed from {} (written by masav {}): step {}, t = {:.6g} s\n", restart_file,
                 resumed->writer, sim.steps(), sim.time());
    resumed.reset();  // the state lives in the simulation now
  }
  if (lead) print_header(sim, o, comm);
  SphRankCounters counters0;
  SphRunEvents events;
  events.started = [&](const SphSimulation& s) {
    if (s.ranks()) counters0 = s.ranks()->counters();
  };
  events.progress = [](const SphSimulation& s) {
    fmt::print("  step {:>7}  t = {:.5f} s  dt = {:.3g} s  max speed {:.3g} m/s\n", s.steps(),
               s.time(), s.last_dt(), s.last_stats().max_speed);
  };
  events.checkpoint = [&](const std::string& path, uint64_t step) {
    if (!o.quiet) fmt::print("  wrote checkpoint {} (step {})\n", path, step);
  };
  events.interrupted = [] { return interrupted(); };
  const SphRunResult r = run.run(sim, events);
  if (sim.ranks() && !r.error) print_rank_table(sim, counters0, lead, r.wall_s, r.steps);
  const bool stopped = !r.error && any_rank_interrupted(r, comm);
  return lead ? report(r, sim, o, stopped) : (r.error ? 1 : stopped ? 130 : 0);
}

}  // namespace

void add_sph_command(CLI::App& app) {
  static SphOptions o;
  auto* cmd =
      add_command(app, "sph", "run an SPH fluid preset headless; export .vtp and CSV", o, run_sph);
  g_sph_command = cmd;
  add_backend_options(*cmd, o.choice, false);
  accept_old_values(cmd->add_option("--preset,-p", o.preset, "scene"))
      ->check(CLI::IsMember(sph_preset_names()))
      ->capture_default_str();
  add_ranged_option(*cmd, "--particles", o.particles, "fluid particles", 1u, 1u << 30);
  add_old_option(*cmd, "-n", "--particles", o.particles)->check(CLI::Range(1u, 1u << 30));
  add_ranged_option(*cmd, "--steps", o.steps, "steps to run (with --restart: further steps)",
                    uint64_t(1), uint64_t(1) << 40);
  cmd->add_option("--time", o.time,
                  "run until this simulated time (s) instead of --steps (with --restart: the "
                  "time since the first run's start)")
      ->check(number_in(0, 1e6, true))
      ->excludes("--steps");
  cmd->add_option("--integrator", o.integrator, "euler, symplectic-euler, rk4 or leapfrog");
  cmd->add_option("--pressure", o.pressure,
                  "pressure model: wcsph, thesis or dfsph (incompressible; symplectic-euler)");
  cmd->add_option("--dt", o.dt, "fixed time step (s); default: CFL-adaptive")
      ->check(number_in(0, 10, true));
  cmd->add_option("--cfl-guard", o.cfl_guard, "reduce (split unstable steps), stop, or off");
  cmd->add_option("--viscosity", o.viscosity, "kinematic viscosity nu (m^2/s; 0: inviscid)")
      ->check(number_in(0, 1e3));
  auto* c0 = cmd->add_option("--sound-speed", o.sound_speed, "wcsph speed of sound c0 (m/s)")
                 ->check(number_in(0, 1e5, true));
  cmd->add_option("--max-compression", o.max_compression,
                  "wcsph: c0 for this largest compression at impacts, c0 = fall speed / it "
                  "(water, mud, dam break, obstacle; the presets' 0.1 is 10 x the fall speed, "
                  "0.03 takes 3.3x the steps)")
      ->check(number_in(0.001, 0.5))
      ->excludes(c0);
  cmd->add_option("--kp", o.kp, "thesis pressure constant (0: no pressure)")
      ->check(number_in(0, 1e12));
  cmd->add_option("--smoothing-radius", o.smoothing_radius, "support radius h (m)")
      ->check(number_in(0, 10, true));
  cmd->add_option("--restitution", o.restitution,
                  "wall restitution in [0, 1] (0: the walls take the normal speed)")
      ->check(number_in(0, 1));
  cmd->add_option("--seed", o.seed, "seed of the particles' jitter (presets with jitter only; 0 is a seed like any other)")
      ->check(CLI::Range(uint64_t(0), uint64_t(1) << 62))
      ->capture_default_str();
  cmd->add_option("--vtp-every", o.vtp_every, "write particles (.vtp) every k steps (0: never)")
      ->check(CLI::Range(uint64_t(0), uint64_t(1) << 40));
  add_ranged_option(*cmd, "--diag-every", o.diag_every, "CSV diagnostics every k steps",
                    uint64_t(1), uint64_t(1) << 40);
  cmd->add_option("--csv", o.csv, "write per-step diagnostics to this CSV file");
  cmd->add_option("--out,-o", o.out,
                  "output directory: .vtp snapshots, the last good state of a failed run "
                  "(default out/sph with --vtp-every)");
  add_ranged_option(*cmd, "--block-steps", o.block_steps,
                    "steps between reads of the step statistics (1: after every step; an "
                    "unstable block is replayed step by step)",
                    1u, SphSimulation::kMaxBlockSteps);
  cmd->add_flag("--quiet,-q", o.quiet, "no progress lines");
  cmd->add_flag("--overwrite", o.overwrite,
                "remove an earlier run's snapshots and last good state from --out first (only "
                "the names a run writes)");
  auto* dir = cmd->add_option("--checkpoint-dir", o.checkpoint_dir,
                              "write DIR/checkpoint.masav: every --checkpoint-every steps, on "
                              "Ctrl-C/SIGTERM and at the end (replaced atomically)");
  add_ranged_option(*cmd, "--checkpoint-every", o.checkpoint_every,
                    "steps between checkpoints (needs --checkpoint-dir)", uint64_t(1),
                    uint64_t(1) << 40)
      ->needs(dir);
  cmd->add_option("--restart", o.restart,
                  "resume the run whose --checkpoint-dir this is (its scene, state and time "
                  "stepping; same trajectory bit for bit on the CPU backend)");
}

}  // namespace masav::app
