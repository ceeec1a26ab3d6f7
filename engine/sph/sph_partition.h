#pragma once
// Which rank owns which cells of the SPH hash grid: contiguous ranges of cell ids, in the grid's
// own order (cell id = (x * dims.y + y) * dims.z + z, so a range is a slab along x with partial
// rows at its ends). A rank then holds a contiguous piece of the array one process would sort,
// which is what keeps a run on several ranks identical to one process (sph_ranks.h).
#include <cstdint>
#include <span>
#include <vector>

namespace masav {

struct SphPartition {
  // ranks + 1 entries, non-decreasing: rank r owns cells [begin[r], begin[r + 1]).
  std::vector<uint32_t> begin;

  int ranks() const { return int(begin.size()) - 1; }
  // The rank owning `cell` (< begin.back()).
  int owner(uint32_t cell) const;
};

// Cells per bucket of the histogram the balance reads: at most kMaxPartitionBuckets buckets,
// so that re-balancing exchanges at most 512 KiB whatever the grid.
inline constexpr uint32_t kMaxPartitionBuckets = 1u << 16;
uint32_t partition_bucket_cells(uint64_t cell_count);

// Ranges balanced by particle count, on bucket boundaries: rank r starts at the first bucket
// before which at least r/ranks of the particles lie. `counts[b]` is the number of particles
// in cells [b * bucket_cells, (b + 1) * bucket_cells). With no particles, equal cell ranges.
SphPartition balance_partition(std::span<const uint64_t> counts, uint32_t bucket_cells,
                               uint32_t cell_count, int ranks);

}  // namespace masav
