#pragma once
// The SPH simulation's state reads: the committed state in particle-id order with density and
// pressure at its positions (evaluated on a re-sorted scratch copy when the last fields belong
// to an older state), a rank's own particles, and on several ranks every rank's gathered.
// Reading the state never changes the trajectory: the committed arrays stay as they are, and an
// open block's stats words get back what the evaluation zeroed (SphStatsKeeper).
#include <cstdint>
#include <optional>
#include <vector>

#include "engine/sph/sph_context.h"

namespace masav {

// For the scope of an evaluation outside the steps: the stats words start from zero and, where
// run() left a block open, get the block's back at the end (its maxima choose the next block's
// dt).
class SphStatsKeeper {
 public:
  SphStatsKeeper(Backend& backend, Buffer<uint32_t>& stats, bool block_open);
  ~SphStatsKeeper();
  SphStatsKeeper(const SphStatsKeeper&) = delete;
  SphStatsKeeper& operator=(const SphStatsKeeper&) = delete;

 private:
  Backend& backend_;
  Buffer<uint32_t>& stats_;
  uint64_t ticket_ = 0;  // the open block's stats words (DeviceApi::read_async)
};

// A state's copies queued by SphStateReader::queue (read_async tickets; 0: taken).
struct SphStateReads {
  uint64_t pos = 0, vel = 0, ids = 0, rho = 0, pr = 0, acc = 0;
};

class SphStateReader {
 public:
  explicit SphStateReader(const SphContext& c) : c_(c) {}

  // SphSimulation::download() and download_own().
  SphState download();
  SphState download_own(std::vector<uint32_t>& ids);

  // download() in two halves (one process): the state's copies queued behind the work so far
  // (density evaluated first where the fields are stale, the open block's stats kept by
  // `keep`), then taken with one wait. drop takes them unread.
  SphStateReads queue(std::optional<SphStatsKeeper>& keep);
  SphState take(SphStateReads& r);
  void drop(SphStateReads& r);

 private:
  SphState take_reads(SphStateReads& r);  // take without the clean-up on an error
  // dfsph's pressure from its density solve's kappa sums (in place) and the densities.
  void dfsph_pressure(std::vector<double>& kappa, const std::vector<double>& rho) const;
  // On several ranks: density and pressure at the committed state's positions.
  void refresh_fields_ranks();
  SphState download_ranks();

  SphContext c_;
};

}  // namespace masav
