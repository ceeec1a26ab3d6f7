#include "engine/sph/sph_run.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <span>

#include "engine/core/error.h"
#include "engine/io/csv_stream.h"
#include "engine/io/output_lock.h"
#include "engine/io/run_outputs.h"
#include "engine/io/writable_paths.h"
#include "engine/sph/sph_checkpoint.h"
#include "engine/sph/sph_diagnostics.h"
#include "engine/sph/sph_export.h"

namespace masav {

// What rank 0 holds open for the run: the locks of its directories and the CSV.
struct SphRun::Outputs {
  std::optional<OutputLock> out_lock, checkpoint_lock;
  std::optional<CsvStream> csv;
  std::optional<RunManifest> manifest;  // of out_dir
};

namespace {

// Every name a run writes into out_dir: snapshots and their pieces and index, the last good
// state, the manifest (never the checkpoint, which a restart may be reading from there).
OutputNames sph_output_names(const std::string& name) {
  return {{name + "_#.vtp", name + "_#_r#.vtp", name + "_#.pvtp", name + "_last_good.vtp",
           name + "_last_good_r#.vtp", name + "_last_good.pvtp", RunManifest::kFileName}};
}

}  // namespace

std::string SphRun::checkpoint_path(const std::string& dir) {
  return (std::filesystem::path(dir) / "checkpoint.masav").string();
}

SphRun::SphRun(const SphRunOptions& o, SphComm* comm)
    : o_(o), comm_(comm), lead_(!comm || comm->rank() == 0), outputs_(std::make_unique<Outputs>()) {
  if (o_.vtp_every && o_.out_dir.empty())
    throw_invalid("sph run", "out_dir", "\"\"", "a directory for the snapshots of vtp_every");
  if (!lead_) return;
  if (!o_.checkpoint_dir.empty()) ensure_writable_dir(o_.checkpoint_dir, "--checkpoint-dir");
  // The directory is only made when something goes there.
  if (!o_.out_dir.empty()) {
    ensure_writable_dir(o_.out_dir, "--out");
    outputs_->out_lock.emplace(o_.out_dir, "--out");
    // Before any rank writes a piece: the simulation's set-up, collective, comes after this.
    claim_outputs(o_.out_dir, sph_output_names(o_.name), o_.overwrite, "--out");
    outputs_->manifest.emplace(o_.out_dir, o_.manifest);
  }
  // Two runs checkpointing into one directory would overwrite each other's state: held too,
  // unless it is the output directory, already held.
  std::error_code same_error;
  if (!o_.checkpoint_dir.empty() &&
      !(outputs_->out_lock &&
        std::filesystem::equivalent(o_.checkpoint_dir, o_.out_dir, same_error)))
    outputs_->checkpoint_lock.emplace(o_.checkpoint_dir, "--checkpoint-dir");
  if (!o_.csv.empty()) outputs_->csv.emplace(o_.csv, diagnostics_columns(), "--csv");
}

SphRun::~SphRun() = default;

SphRunResult SphRun::run(SphSimulation& sim, const SphRunEvents& events) {
  namespace fs = std::filesystem;
  SphRunResult result;
  uint64_t checkpointed = UINT64_MAX;  // the step of the last checkpoint written
  // Writes one unless the last holds this step already; returns its path.
  auto checkpoint = [&] {
    const std::string path = checkpoint_path(o_.checkpoint_dir);
    if (checkpointed != sim.steps()) {
      const SphResumeState state = sim.export_resume_state();  // every rank's part
      if (lead_) write_sph_checkpoint(path, sim.scene(), state);
    }
    checkpointed = sim.steps();
    return path;
  };
  auto record = [&](const SphState& st) {
    if (outputs_->csv) outputs_->csv->row(diagnostics_row(sim, compute_diagnostics(st, sim)));
  };
  // One .vtp of every particle; on several ranks each rank's piece and rank 0's .pvtp index.
  auto snapshot = [&](const std::optional<SphState>& all, const std::string& tag) {
    if (!comm_) {
      const std::string file = fmt::format("{}_{}.vtp", o_.name, tag);
      const std::string path = (fs::path(o_.out_dir) / file).string();
      if (outputs_->manifest) outputs_->manifest->add(file);
      write_sph_vtp(path, all ? *all : sim.download());
      return path;
    }
    auto piece = [&](int r) { return fmt::format("{}_{}_r{}.vtp", o_.name, tag, r); };
    std::vector<uint32_t> ids;
    const SphState mine = sim.download_own(ids);
    write_sph_vtp((fs::path(o_.out_dir) / piece(comm_->rank())).string(), mine, ids);
    std::vector<std::string> pieces;
    for (int r = 0; r < comm_->size(); ++r) pieces.push_back(piece(r));
    const std::string index = fmt::format("{}_{}.pvtp", o_.name, tag);
    const std::string path = (fs::path(o_.out_dir) / index).string();
    if (outputs_->manifest) {  // rank 0's: every rank's piece, and the index
      for (const std::string& p : pieces) outputs_->manifest->add(p);
      outputs_->manifest->add(index);
    }
    if (lead_) write_sph_pvtp(path, pieces);
    return path;
  };
  // Whether any rank was interrupted: they stop together, at the same step.
  auto stop_requested = [&] {
    uint32_t flag = events.interrupted && events.interrupted() ? 1u : 0u;
    if (comm_) comm_->max(std::span<uint32_t>(&flag, 1));
    return flag != 0;
  };
  const bool time_run = o_.t_end > 0;
  // Steps from step k (counted from the run's start, a restart's included) to the next one that
  // records diagnostics, writes a snapshot or a checkpoint or reports progress (or to `end` in a
  // step-count run), at most one block.
  auto steps_to_next_event = [&](uint64_t k, uint64_t end) {
    auto to_multiple = [k](uint64_t every) { return every - k % every; };
    uint64_t n = time_run ? std::numeric_limits<uint64_t>::max() : end - k;
    if (!o_.csv.empty()) n = std::min(n, to_multiple(o_.diag_every));
    if (o_.vtp_every) n = std::min(n, to_multiple(o_.vtp_every));
    if (o_.checkpoint_every) n = std::min(n, to_multiple(o_.checkpoint_every));
    if (o_.progress_every) n = std::min(n, to_multiple(o_.progress_every));
    return std::min<uint64_t>(n, sim.block_steps());
  };

  if (!o_.csv.empty() || o_.vtp_every) {
    std::optional<SphState> st;
    if (!o_.csv.empty()) record(*(st = sim.download()));
    if (o_.vtp_every) snapshot(st, fmt::format("{:06}", 0));
  }
  if (events.started) events.started(sim);
  const auto t0 = std::chrono::steady_clock::now();
  const uint64_t steps0 = sim.steps(), substeps0 = sim.substeps();
  try {
    const double t_end = time_run ? o_.t_end : std::numeric_limits<double>::infinity();
    // Steps are counted from the run's start: a restart continues the count, and the events
    // (and with them the blocks) fall on the same steps as in an uninterrupted run.
    const uint64_t end = sim.steps() + o_.steps;
    for (uint64_t k = sim.steps(); (time_run ? sim.time() < o_.t_end : k < end);) {
      if (stop_requested()) {
        result.interrupted = true;
        break;
      }
      // Up to the next step that prints or writes something (at most one block, so that an
      // interrupt is seen): the simulation reads its stats back once per block.
      k += sim.run(steps_to_next_event(k, end), t_end);
      const bool diag = !o_.csv.empty() && k % o_.diag_every == 0;
      const bool vtp = o_.vtp_every && k % o_.vtp_every == 0;
      if (diag || vtp) {
        std::optional<SphState> st;  // every particle: for the CSV, and one process's .vtp
        if (diag) record(*(st = sim.download()));
        if (vtp) snapshot(st, fmt::format("{:06}", k));
      }
      if (lead_ && o_.progress_every && k % o_.progress_every == 0 && events.progress)
        events.progress(sim);
      if (o_.checkpoint_every && k % o_.checkpoint_every == 0) {
        const std::string path = checkpoint();
        if (lead_ && events.checkpoint) events.checkpoint(path, k);
      }
    }
    // At the step where the run ends or an interrupt stopped it (a failed run keeps the last).
    if (!o_.checkpoint_dir.empty()) result.final_checkpoint = checkpoint();
  } catch (const Error& e) {
    result.error = e.what();
    // On several ranks, an error of the simulation's own checks (decided on reduced values) was
    // raised by every rank at the same step, so they write the last good state together (a
    // piece each and the index); any other error may have stopped one rank alone, and a
    // collective write would wait for the others forever.
    if (!o_.out_dir.empty() && (!comm_ || sim.failed_together()))
      result.last_good = snapshot(std::nullopt, "last_good");
    else if (comm_)
      result.last_good_skipped = true;
  }
  result.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  // The rows written become the file (the old one stayed whole until now), whatever ended the
  // run: its end, an interrupt or an error.
  if (outputs_->csv) outputs_->csv->commit();
  result.steps = sim.steps() - steps0;
  result.substeps = sim.substeps() - substeps0;
  result.csv_rows = outputs_->csv ? outputs_->csv->rows() : 0;
  if (outputs_->manifest)
    outputs_->manifest->write(result.error         ? "failed"
                              : result.interrupted ? "interrupted"
                                                   : "completed");
  return result;
}

}  // namespace masav
