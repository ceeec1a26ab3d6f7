#pragma once
// An SPH run with its outputs: what a program needs around SphSimulation to run it as `masav sph`
// does. The run
//   - opens and holds its outputs before any simulation exists, so a bad path fails at once: the
//     output directory (.vtp snapshots, the last good state) and the checkpoint directory, each
//     locked against a second run (engine/io/output_lock.h), and the per-step CSV, whose rows
//     reach a partial file as their steps end and replace the old file when the run ends,
//     however it ends (a run refused before its first step leaves the old file whole);
//   - steps the simulation in calls of at most one block, from one event to the next (a CSV row,
//     a snapshot, a checkpoint, a progress report), so the events fall on the same steps however
//     the run is split by restarts, and an interrupt is seen within a block;
//   - writes a checkpoint every k steps, at the end and when interrupted (atomically replaced);
//   - on an error of the simulation, writes the last good state beside the snapshots;
//   - owns out_dir: an earlier run's files of its names are refused (removed with overwrite),
//     and out_dir/manifest.json lists the files this run wrote and how it ended.
// On several ranks every rank takes part in each gather; rank 0 writes the CSV, the checkpoints
// and the .pvtp index, each rank its snapshot piece. Nothing here prints: events go to the
// caller's callbacks.
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "engine/sph/sph_comm.h"
#include "engine/sph/sph_simulation.h"

namespace masav {

struct SphRunOptions {
  uint64_t steps = 100;  // further steps, counted from the simulation's current step
  // > 0: run until this simulated time instead of a step count.
  double t_end = 0;
  std::string csv;  // per-step diagnostics (engine/sph/sph_diagnostics.h); "" for none
  uint64_t diag_every = 1;
  std::string out_dir;     // snapshots and the last good state; "" for none
  std::string name = "sph";  // file names: NAME_STEP.vtp (and NAME_STEP_rR.vtp, .pvtp on ranks)
  uint64_t vtp_every = 0;  // a snapshot every k steps (and of the start); 0 for none
  std::string checkpoint_dir;  // DIR/checkpoint.masav; "" for none
  uint64_t checkpoint_every = 0;  // 0: only at the end and on an interrupt
  uint64_t progress_every = 100;  // steps between progress events; 0 for none
  // An earlier run's snapshots and last good state in out_dir are refused unless this is set,
  // and then removed (only those names: engine/io/run_outputs.h).
  bool overwrite = false;
  // What out_dir/manifest.json says the run was (command, preset, ...), beside its files.
  std::vector<std::pair<std::string, std::string>> manifest;
};

struct SphRunEvents {
  // Once the start's outputs are written, right before the first step (every rank).
  std::function<void(const SphSimulation&)> started;
  // Every progress_every steps (rank 0 only).
  std::function<void(const SphSimulation&)> progress;
  // A periodic checkpoint was written (rank 0 only).
  std::function<void(const std::string& path, uint64_t step)> checkpoint;
  // Polled between calls of the simulation: whether this process was asked to stop. Any rank's
  // request stops every rank, at the same step.
  std::function<bool()> interrupted;
};

struct SphRunResult {
  uint64_t steps = 0, substeps = 0;  // this run's (a restart's totals include earlier runs')
  double wall_s = 0;
  bool interrupted = false;
  std::optional<std::string> error;  // the simulation's error, when it stopped with one
  std::string last_good;  // where the last good state went after an error ("" if nowhere)
  // On several ranks, after an error that may have stopped one rank alone: why no last good
  // state was written.
  bool last_good_skipped = false;
  std::string final_checkpoint;  // the checkpoint written at the end ("" without a directory)
  uint64_t csv_rows = 0;
};

class SphRun {
 public:
  // Checks and holds the outputs of `o` (throws masav::Error naming the option on a path that
  // cannot be used or is held by another run).
  SphRun(const SphRunOptions& o, SphComm* comm);
  ~SphRun();
  SphRun(const SphRun&) = delete;
  SphRun& operator=(const SphRun&) = delete;

  // Runs `sim` (created after the outputs, with the same communicator) to the options' end.
  // Errors of the simulation are caught and reported in the result; others are thrown.
  SphRunResult run(SphSimulation& sim, const SphRunEvents& events = {});

  static std::string checkpoint_path(const std::string& dir);  // DIR/checkpoint.masav

 private:
  struct Outputs;
  SphRunOptions o_;
  SphComm* comm_;
  bool lead_;
  std::unique_ptr<Outputs> outputs_;
};

}  // namespace masav
