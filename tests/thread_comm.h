#pragma once
// Ranks as threads of one process: an SphComm for each of N threads that exchange through
// shared memory, so the tests run a simulation on several ranks on every backend without MPI.
// Each collective: every rank leaves its part in a slot, waits for all, reads the others', and
// waits again before the slots are reused.
#include <algorithm>
#include <condition_variable>
#include <functional>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include "engine/sph/sph_comm.h"

namespace masav::test {

class ThreadHub {
 public:
  explicit ThreadHub(int ranks)
      : boxes_(size_t(ranks)), words_(size_t(ranks)), sums_(size_t(ranks)), ranks_(ranks) {}
  int ranks() const { return ranks_; }

  void barrier() {
    std::unique_lock lock(mutex_);
    const uint64_t generation = generation_;
    if (++arrived_ == ranks_) {
      arrived_ = 0;
      ++generation_;
      cv_.notify_all();
    } else {
      cv_.wait(lock, [&] { return generation_ != generation; });
    }
  }

  std::vector<std::vector<Bytes>> boxes_;  // [from][to]
  std::vector<std::vector<uint32_t>> words_;
  std::vector<std::vector<uint64_t>> sums_;

 private:
  int ranks_;
  std::mutex mutex_;
  std::condition_variable cv_;
  int arrived_ = 0;
  uint64_t generation_ = 0;
};

class ThreadComm final : public SphComm {
 public:
  ThreadComm(ThreadHub& hub, int rank) : hub_(hub), rank_(rank) {}
  int rank() const override { return rank_; }
  int size() const override { return hub_.ranks(); }

  std::vector<Bytes> exchange(const std::vector<Bytes>& to) override {
    hub_.boxes_[size_t(rank_)] = to;
    hub_.boxes_[size_t(rank_)].resize(size_t(size()));
    hub_.barrier();
    std::vector<Bytes> from(static_cast<size_t>(size()));
    for (int r = 0; r < size(); ++r)
      if (r != rank_) from[size_t(r)] = hub_.boxes_[size_t(r)][size_t(rank_)];
    hub_.barrier();
    return from;
  }
  // The messages wait in the slots until finish(), which every rank calls before its next
  // collective (the slots are free again: the last collective ended with a barrier).
  std::unique_ptr<SphPendingExchange> start_exchange(std::vector<Bytes> to,
                                                     std::vector<size_t>) override {
    hub_.boxes_[size_t(rank_)] = std::move(to);
    hub_.boxes_[size_t(rank_)].resize(size_t(size()));
    struct Pending final : SphPendingExchange {
      ThreadComm* comm;
      std::vector<Bytes> finish() override {
        ThreadHub& hub = comm->hub_;
        hub.barrier();
        std::vector<Bytes> from(static_cast<size_t>(comm->size()));
        for (int r = 0; r < comm->size(); ++r)
          if (r != comm->rank_) from[size_t(r)] = hub.boxes_[size_t(r)][size_t(comm->rank_)];
        hub.barrier();
        return from;
      }
    };
    auto p = std::make_unique<Pending>();
    p->comm = this;
    return p;
  }
  void max(std::span<uint32_t> values) override {
    hub_.words_[size_t(rank_)].assign(values.begin(), values.end());
    hub_.barrier();
    for (int r = 0; r < size(); ++r)
      for (size_t i = 0; i < values.size(); ++i)
        values[i] = std::max(values[i], hub_.words_[size_t(r)][i]);
    hub_.barrier();
  }
  void sum(std::span<uint64_t> values) override {
    hub_.sums_[size_t(rank_)].assign(values.begin(), values.end());
    hub_.barrier();
    for (size_t i = 0; i < values.size(); ++i) {
      uint64_t s = 0;
      for (int r = 0; r < size(); ++r) s += hub_.sums_[size_t(r)][i];
      values[i] = s;
    }
    hub_.barrier();
  }
  std::vector<Bytes> allgather(std::span<const std::byte> mine) override {
    std::vector<Bytes> to(size_t(size()), Bytes(mine.begin(), mine.end()));
    std::vector<Bytes> all = exchange(to);
    all[size_t(rank_)].assign(mine.begin(), mine.end());
    return all;
  }

 private:
  ThreadHub& hub_;
  int rank_;
};

// Runs body(comm) on `ranks` threads, one rank each; rethrows the first exception.
inline void run_ranks(int ranks, const std::function<void(SphComm&)>& body) {
  ThreadHub hub(ranks);
  std::vector<std::exception_ptr> errors(static_cast<size_t>(ranks));
  std::vector<std::thread> threads;
  for (int r = 0; r < ranks; ++r)
    threads.emplace_back([&, r] {
      ThreadComm comm(hub, r);
      try {
        body(comm);
      } catch (...) {
        errors[size_t(r)] = std::current_exception();
      }
    });
  for (auto& t : threads) t.join();
  for (auto& e : errors)
    if (e) std::rethrow_exception(e);
}

}  // namespace masav::test
