#include "app/mpi_comm.h"

#include <fmt/format.h>

#include <climits>
#include <cstdlib>
#include <string>

#include "engine/core/error.h"

#if MASAV_HAVE_MPI
#include <mpi.h>
#if __has_include(<mpi-ext.h>)
#include <mpi-ext.h>  // OpenMPI's extensions: MPIX_CUDA_AWARE_SUPPORT, MPIX_Query_cuda_support
#endif
#endif

namespace masav::app {

int launched_ranks() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE"}) {
    if (const char* v = std::getenv(name)) {
      char* end = nullptr;
      const long n = std::strtol(v, &end, 10);
      if (end != v && *end == '\0' && n >= 1 && n <= INT_MAX) return int(n);
    }
  }
  return 1;
}

int local_rank() {
  for (const char* name : {"OMPI_COMM_WORLD_LOCAL_RANK", "MPI_LOCALRANKID"}) {
    if (const char* v = std::getenv(name)) {
      char* end = nullptr;
      const long r = std::strtol(v, &end, 10);
      if (end != v && *end == '\0' && r >= 0 && r < INT_MAX) return int(r);
    }
  }
  return -1;
}

#if MASAV_HAVE_MPI
namespace {

void check(int rc, const char* call) {
  if (rc == MPI_SUCCESS) return;
  char text[MPI_MAX_ERROR_STRING];
  int len = 0;
  MPI_Error_string(rc, text, &len);
  throw Error("mpi", call, std::string(text, size_t(len)),
              "check the MPI installation and that every rank runs the same masav");
}

// MPI counts are ints: one exchange moves at most INT_MAX bytes per rank.
int count_of(size_t bytes, const char* what) {
  if (bytes > size_t(INT_MAX))
    throw Error("mpi", what, fmt::format("{} bytes in one exchange", bytes),
                "at most 2 GiB per rank and exchange: run on more ranks");
  return int(bytes);
}

// An MPI_Ialltoallv in flight: its buffers live until it is waited for.
struct Pending final : SphPendingExchange {
  Bytes send, recv;
  std::vector<int> send_counts, send_at, recv_counts, recv_at;
  MPI_Request request = MPI_REQUEST_NULL;
  std::vector<Bytes> finish() override {
    check(MPI_Wait(&request, MPI_STATUS_IGNORE), "MPI_Wait");
    std::vector<Bytes> from(recv_counts.size());
    for (size_t r = 0; r < from.size(); ++r)
      from[r].assign(recv.begin() + recv_at[r], recv.begin() + recv_at[r] + recv_counts[r]);
    return from;
  }
  ~Pending() override {
    if (request != MPI_REQUEST_NULL) MPI_Wait(&request, MPI_STATUS_IGNORE);
  }
};

class MpiComm final : public SphComm {
 public:
  MpiComm() {
    check(MPI_Comm_rank(MPI_COMM_WORLD, &rank_), "MPI_Comm_rank");
    check(MPI_Comm_size(MPI_COMM_WORLD, &size_), "MPI_Comm_size");
  }
  int rank() const override { return rank_; }
  int size() const override { return size_; }

  std::vector<Bytes> exchange(const std::vector<Bytes>& to) override {
    // The sizes first, then the messages.
    const size_t n = size_t(size_);
    std::vector<int> send_counts(n, 0), recv_counts(n, 0);
    for (size_t r = 0; r < n && r < to.size(); ++r)
      if (int(r) != rank_) send_counts[r] = count_of(to[r].size(), "exchange");
    check(MPI_Alltoall(send_counts.data(), 1, MPI_INT, recv_counts.data(), 1, MPI_INT,
                       MPI_COMM_WORLD),
          "MPI_Alltoall");
    return start_exchange(to, std::vector<size_t>(recv_counts.begin(), recv_counts.end()))
        ->finish();
  }

  std::unique_ptr<SphPendingExchange> start_exchange(std::vector<Bytes> to,
                                                     std::vector<size_t> sizes) override {
    const size_t n = size_t(size_);
    auto p = std::make_unique<Pending>();
    p->send_counts.assign(n, 0);
    p->send_at.assign(n, 0);
    p->recv_counts.assign(n, 0);
    p->recv_at.assign(n, 0);
    size_t sent = 0, received = 0;
    for (size_t r = 0; r < n; ++r) {
      if (int(r) == rank_) continue;
      p->send_at[r] = count_of(sent, "exchange");
      p->send_counts[r] = count_of(r < to.size() ? to[r].size() : 0, "exchange");
      sent += size_t(p->send_counts[r]);
      p->recv_at[r] = count_of(received, "exchange");
      p->recv_counts[r] = count_of(r < sizes.size() ? sizes[r] : 0, "exchange");
      received += size_t(p->recv_counts[r]);
    }
    p->send.reserve(sent);
    for (size_t r = 0; r < n; ++r)
      if (p->send_counts[r]) p->send.insert(p->send.end(), to[r].begin(), to[r].end());
    p->recv.resize(received);
    check(MPI_Ialltoallv(p->send.data(), p->send_counts.data(), p->send_at.data(), MPI_BYTE,
                         p->recv.data(), p->recv_counts.data(), p->recv_at.data(), MPI_BYTE,
                         MPI_COMM_WORLD, &p->request),
          "MPI_Ialltoallv");
    return p;
  }

  void max(std::span<uint32_t> values) override {
    check(MPI_Allreduce(MPI_IN_PLACE, values.data(), int(values.size()), MPI_UINT32_T, MPI_MAX,
                        MPI_COMM_WORLD),
          "MPI_Allreduce");
  }
  void sum(std::span<uint64_t> values) override {
    check(MPI_Allreduce(MPI_IN_PLACE, values.data(), int(values.size()), MPI_UINT64_T, MPI_SUM,
                        MPI_COMM_WORLD),
          "MPI_Allreduce");
  }

  std::vector<Bytes> allgather(std::span<const std::byte> mine) override {
    const size_t n = size_t(size_);
    int count = count_of(mine.size(), "allgather");
    std::vector<int> counts(n), at(n);
    check(MPI_Allgather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, MPI_COMM_WORLD),
          "MPI_Allgather");
    size_t total = 0;
    for (size_t r = 0; r < n; ++r) {
      at[r] = count_of(total, "allgather");
      total += size_t(counts[r]);
    }
    Bytes all(total);
    count_of(total, "allgather");
    check(MPI_Allgatherv(mine.data(), count, MPI_BYTE, all.data(), counts.data(), at.data(),
                         MPI_BYTE, MPI_COMM_WORLD),
          "MPI_Allgatherv");
    std::vector<Bytes> out(n);
    for (size_t r = 0; r < n; ++r)
      out[r].assign(all.begin() + at[r], all.begin() + at[r] + counts[r]);
    return out;
  }

 private:
  int rank_ = 0, size_ = 1;
};

}  // namespace

SphComm* world_comm() {
  if (launched_ranks() <= 1) return nullptr;
  static std::unique_ptr<MpiComm> comm = [] {
    int initialized = 0;
    MPI_Initialized(&initialized);
    if (!initialized) {
      check(MPI_Init(nullptr, nullptr), "MPI_Init");
      std::atexit([] {
        int finalized = 0;
        MPI_Finalized(&finalized);
        if (!finalized) MPI_Finalize();
      });
    }
    return std::make_unique<MpiComm>();
  }();
  return comm->size() > 1 ? comm.get() : nullptr;
}

std::string exchange_path() {
#if defined(MPIX_CUDA_AWARE_SUPPORT) && MPIX_CUDA_AWARE_SUPPORT
  if (MPIX_Query_cuda_support() == 1)
    return "staged through host memory (this MPI is CUDA-aware; masav does not pass it GPU "
           "memory)";
#endif
  return "staged through host memory (this MPI is not CUDA-aware)";
}

#else

std::string exchange_path() {
  return "none (no MPI)";
}

SphComm* world_comm() {
  const int n = launched_ranks();
  if (n <= 1) return nullptr;
  throw Error("", "ranks", fmt::format("started on {} ranks, but this masav has no MPI", n),
              "install libopenmpi-dev (tools/setup does) and rebuild, or run one process");
}

#endif

}  // namespace masav::app
