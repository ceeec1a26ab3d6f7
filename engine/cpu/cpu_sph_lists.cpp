#include "engine/cpu/cpu_sph_lists.h"

#include <algorithm>
#include <atomic>
#include <cstring>

namespace masav::cpu {
namespace {

// The kept copy against the array now, compared in pieces on the pool: every kernel that reads
// the lists compares its positions and cells (a DFSPH step a dozen times), which on one thread
// took a few percent of a small simulation's step.
template <class T>
bool same(ThreadPool& pool, const std::vector<T>& kept, const T* now, size_t count) {
  if (kept.size() != count) return false;
  std::atomic<bool> equal{true};
  pool.parallel_for(count * sizeof(T), 65536, [&](size_t b, size_t e) {
    if (equal.load(std::memory_order_relaxed) &&
        std::memcmp(reinterpret_cast<const char*>(kept.data()) + b,
                    reinterpret_cast<const char*>(now) + b, e - b) != 0)
      equal.store(false, std::memory_order_relaxed);
  });
  return equal.load();
}

}  // namespace

void SphNeighborLists::reset(uint32_t n, size_t chunks) {
  valid_ = false;
  ++generation_;
  index_.resize(chunks);
  for (auto& l : index_) l.clear();
  begin_.resize(n);
  chunk_of_.resize(n);
  count_.resize(n);
  candidates_.resize(n);
  overflow_.resize(n);
}

void SphNeighborLists::remember(const SphListInputs& in) {
  n_ = in.n;
  first_ = in.first;
  end_ = in.end;
  max_candidates_ = in.max_candidates;
  std::copy(in.dims, in.dims + 3, dims_);
  h2_ = in.h2;
  fp32_ = in.fp32;
  positions_.assign(in.positions, in.positions + 4 * size_t(in.n));
  cells_.assign(in.cells, in.cells + in.n);
  cell_start_.assign(in.cell_start, in.cell_start + in.cell_count);
  cell_end_.assign(in.cell_end, in.cell_end + in.cell_count);
  valid_ = true;
}

bool SphNeighborLists::matches(const SphListInputs& in, ThreadPool& pool) const {
  return valid_ && in.n == n_ && in.first >= first_ && in.end <= end_ &&
         in.max_candidates == max_candidates_ && std::equal(in.dims, in.dims + 3, dims_) &&
         in.h2 == h2_ && in.fp32 == fp32_ &&
         same(pool, positions_, in.positions, 4 * size_t(in.n)) &&
         same(pool, cells_, in.cells, in.n) &&
         same(pool, cell_start_, in.cell_start, in.cell_count) &&
         same(pool, cell_end_, in.cell_end, in.cell_count);
}

void SphNeighborLists::append(size_t chunk, uint32_t i, const uint32_t* neighbors, uint32_t count,
                              uint32_t candidates, bool overflow) {
  std::vector<uint32_t>& l = index_[chunk];
  begin_[i] = l.size();
  chunk_of_[i] = uint32_t(chunk);
  l.insert(l.end(), neighbors, neighbors + count);
  count_[i] = count;
  candidates_[i] = candidates;
  overflow_[i] = overflow ? 1 : 0;
}

}  // namespace masav::cpu
