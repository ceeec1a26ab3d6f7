#pragma once
// One SPH simulation shared among ranks (processes, or threads in the tests), each driving its
// own backend: the decomposition, the migration of particles between ranks and the halo
// exchange. The field evaluator (sph_field_evaluator.h) calls it where one process would
// rebuild its grid; sph_rank_gather.h reads and gathers the ranks' own particles.
//
// Identical to one process. One process keeps its particles sorted by cell, stably (within a
// cell in the order of the previous sort), and sums over neighbours in that order. A rank owns a
// contiguous range of cell ids (sph_partition.h), so its particles are a contiguous piece of
// that one-process array, and the pieces of the ranks, in rank order, are the whole array. At a
// rebuild each rank sends the particles that left its range to their new owners; the receiver
// puts those from lower ranks before its own and those from higher ranks after, which is their
// order in the one-process array, and sorts stably by cell: the same order one process gets.
// Then each rank sends every particle of a cell next to another rank's range (the 27 cells
// around it) to that rank, in its order: halo cells arrive whole and in the one-process order,
// before the rank's own cells (from lower ranks) or after them (from higher ranks). The local
// arrays are [halos of lower cells][own][halos of higher cells], sorted by cell like the
// one-process array, and a kernel computing only the own range walks the same neighbours in the
// same order as one process: the same bits, on every backend. Stats are maxima (and one sum of
// counts) over the ranks, exact, so every rank chooses the same dt.
//
// Data moves through host memory (download, exchange, upload).
#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <utility>
#include <vector>

#include "engine/kernels/backend.h"
#include "engine/sph/sph_comm.h"
#include "engine/sph/sph_partition.h"

namespace masav {

// Where a rank's particles sit in its local arrays.
struct SphRankLayout {
  uint32_t local = 0;  // own and halo particles
  uint32_t first = 0;  // own particles: [first, first + own)
  uint32_t own = 0;
};

// What the exchanges cost, summed since the simulation started (this rank's share).
struct SphRankCounters {
  uint64_t rebuilds = 0;      // redistribute() calls
  uint64_t migrated = 0;      // particles received from other ranks at rebuilds
  uint64_t halo = 0;          // halo particles received at rebuilds
  uint64_t halo_updates = 0;  // halo updates (density and pressure together count once)
  uint64_t overlapped = 0;    // own particles whose forces ran while their halos travelled
  uint64_t bytes_sent = 0;    // to other ranks, all exchanges
  uint64_t rebalances = 0;
  double exchange_seconds = 0;  // in the exchanges, host work and waiting included
  double mpi_seconds = 0;       // of those, inside the transfers (and waiting for other ranks)
  double reduce_seconds = 0;    // in the step statistics' reductions (every rank waits for all)
};

// A per-particle array that moves with the particles at a rebuild (SphRanks::redistribute): read
// from `from` in the committed layout, written to `to` in the staged one, halos included.
class SphCarried {
 public:
  SphCarried(const Buffer<Real4>& from, Buffer<Real4>& to) : from4_(&from), to4_(&to) {}
  SphCarried(const Buffer<Real>& from, Buffer<Real>& to) : from1_(&from), to1_(&to) {}
  const BufferImpl& from() const { return from4_ ? from4_->impl() : from1_->impl(); }
  // Resolved when written: the rank's buffers may have grown (on_reserve) since the read.
  BufferImpl& to() const { return to4_ ? to4_->impl() : to1_->impl(); }
  size_t bytes(const Backend& b) const { return (from4_ ? 4 : 1) * b.real_bytes(); }

 private:
  const Buffer<Real4>* from4_ = nullptr;
  Buffer<Real4>* to4_ = nullptr;
  const Buffer<Real>* from1_ = nullptr;
  Buffer<Real>* to1_ = nullptr;
};

class SphRanks {
 public:
  SphRanks(SphComm& comm, Backend& backend, const GridParams& grid);

  // Called with the number of particles this rank is about to hold (own and halos) before they
  // are written to the caller's buffers (redistribute, scatter_by_id), so that buffers sized
  // for a rank's share grow when it takes more: the simulation's per-rank capacity.
  void on_reserve(std::function<void(uint32_t)> reserve) { reserve_ = std::move(reserve); }

  int rank() const { return comm_.rank(); }
  int ranks() const { return comm_.size(); }
  const SphRankCounters& counters() const { return counters_; }

  // This rank's share of all particles (given by id, the same on every rank), in id order: its
  // own particles, without halos, become the committed layout (the next redistribute() adds the
  // halos). `balance`: first balance the partition for these particles.
  void scatter_by_id(const std::vector<Vec4d>& positions, const std::vector<Vec4d>& velocities,
                     bool balance, Buffer<Real4>& x, Buffer<Real4>& v, Buffer<uint32_t>& ids);
  // Balances the partition for all particles' positions (the same on every rank).
  void balance(const std::vector<Vec4d>& positions);
  // This rank's share [first, end) of `count` values in the one-process order (the order of a
  // rebuild): equal contiguous pieces in rank order, which redistribute() accepts as the
  // committed layout wherever the particles are.
  std::pair<size_t, size_t> share(size_t count) const;

  // The rebuild's exchange (see the header): the own particles of the committed layout of x,
  // v, ids (and the `carried` arrays, which move with them) go to their cells' owners,
  // re-balancing first when the fullest rank holds more than kImbalance above the mean (and
  // kImbalance above what the last balance could reach); the result,
  // halos included, is written to the *_out buffers (which may not be the inputs) in the new,
  // staged layout. The inputs keep the committed layout until commit().
  static constexpr double kImbalance = 0.10;
  const SphRankLayout& redistribute(const Buffer<Real4>& x, const Buffer<Real4>& v,
                                    const Buffer<uint32_t>& ids,
                                    std::span<const SphCarried> carried, Buffer<Real4>& x_out,
                                    Buffer<Real4>& v_out, Buffer<uint32_t>& ids_out);
  const SphRankLayout& committed() const { return committed_; }
  const SphRankLayout& staged() const { return staged_; }  // the grid's: the last redistribute
  void commit() { committed_ = staged_; }                  // the staged arrays became the state
  void restore(const SphRankLayout& committed);            // a checkpoint's state, no halos

  // The staged layout's halo slots of `b` get their owners' values (whose own values a kernel
  // wrote since the rebuild).
  void exchange_halos(Buffer<Real4>& a, Buffer<Real4>& b);  // both arrays in one exchange
  void exchange_halos(Buffer<Real4>& a);
  void exchange_halos(Buffer<Real>& a);
  // The same for two arrays, started: the caller computes what needs no halo (interior()) while
  // the values travel, then calls finish_halos() before anything else of this object.
  void start_halos(Buffer<Real>& a, Buffer<Real>& b);
  void finish_halos();
  // The own particles none of whose neighbours is a halo, [begin, end) in the local arrays: the
  // middle of the own range (cells next to another rank's are at its ends).
  std::pair<uint32_t, uint32_t> interior() const;
  void count_overlapped(uint32_t particles) { counters_.overlapped += particles; }

  // kSphStatWords stats words: maxima over the ranks, the outside counts summed.
  void reduce_stats(uint32_t* words);
  // The smallest of the ranks' values.
  uint32_t min(uint32_t value);
  // The sum of the ranks' values (integers: exact, in any order).
  uint64_t sum(uint64_t value);
  // The ranks' `mine`, concatenated in rank order, on every rank.
  Bytes gather(const Bytes& mine);

 private:
  class Timer;
  using HaloArrays = std::vector<std::pair<BufferImpl*, size_t>>;  // buffer, bytes per element
  void start_halos(HaloArrays arrays);
  // comm_.exchange, its time counted as in MPI.
  std::vector<Bytes> transfer(const std::vector<Bytes>& out);
  uint32_t cell_of(const std::byte* real4) const;
  std::vector<uint32_t> cells_of(const std::vector<Vec4d>& positions) const;
  void maybe_rebalance(const std::vector<uint32_t>& cells);
  SphPartition partition_for(const std::vector<uint32_t>& cells, bool global);

  SphComm& comm_;
  Backend& backend_;
  GridParams grid_;
  uint32_t cell_count_ = 0;
  SphPartition partition_;
  double reachable_ = 0;  // the imbalance the last balance reached (max / mean - 1)
  SphRankLayout committed_, staged_;
  // The staged layout's halo traffic: own indices (relative to first) sent to each rank, and
  // how many particles each rank sent here.
  std::vector<std::vector<uint32_t>> halo_send_;
  std::vector<uint32_t> halo_recv_;
  // Own indices below lo_end_ go to lower ranks, from hi_begin_ on to higher ranks.
  uint32_t lo_end_ = 0, hi_begin_ = 0;
  HaloArrays pending_arrays_;  // a started halo update
  std::unique_ptr<SphPendingExchange> pending_;
  std::function<void(uint32_t)> reserve_;  // see on_reserve
  SphRankCounters counters_;
};

// Adds the scope's wall time to a counter (SphRankCounters).
class SphRanks::Timer {
 public:
  explicit Timer(double& total) : total_(total), start_(std::chrono::steady_clock::now()) {}
  ~Timer() {
    total_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }

 private:
  double& total_;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace masav
