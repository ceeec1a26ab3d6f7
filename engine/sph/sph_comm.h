#pragma once
// What an SPH simulation shared among ranks needs from the processes it runs in: their number,
// this one's rank, and four collectives. MPI provides it in masav (app/mpi_comm.cpp, built when
// CMake finds MPI); the tests also run ranks as threads of one process (tests/thread_comm.h).
// Every rank calls the collectives in the same order, as MPI requires.
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <memory>
#include <span>
#include <vector>

namespace masav {

using Bytes = std::vector<std::byte>;

// An exchange under way (SphComm::start_exchange): finish() waits for it and returns what each
// rank sent to this one.
class SphPendingExchange {
 public:
  virtual ~SphPendingExchange() = default;
  virtual std::vector<Bytes> finish() = 0;
};

class SphComm {
 public:
  virtual ~SphComm() = default;
  virtual int rank() const = 0;
  virtual int size() const = 0;
  // to[r] goes to rank r (to[rank()] is not sent); returns what each rank sent to this one.
  virtual std::vector<Bytes> exchange(const std::vector<Bytes>& to) = 0;
  // exchange() without waiting, for messages whose sizes the receivers know (sizes[r]: the bytes
  // rank r sends here): the caller computes while they travel and calls finish() before its next
  // collective.
  virtual std::unique_ptr<SphPendingExchange> start_exchange(std::vector<Bytes> to,
                                                             std::vector<size_t> sizes) = 0;
  // Element-wise maximum / sum over the ranks, in place (the same result on every rank).
  virtual void max(std::span<uint32_t> values) = 0;
  virtual void sum(std::span<uint64_t> values) = 0;
  // Every rank's `mine`, indexed by rank, on every rank.
  virtual std::vector<Bytes> allgather(std::span<const std::byte> mine) = 0;
};

// Raw copies of trivially copyable values into and out of byte strings.
template <class T>
void append_bytes(Bytes& out, std::span<const T> values) {
  const size_t at = out.size();
  out.resize(at + values.size_bytes());
  if (!values.empty()) std::memcpy(out.data() + at, values.data(), values.size_bytes());
}

}  // namespace masav
