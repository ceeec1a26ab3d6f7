#include "engine/sph/sph_partition.h"

#include <algorithm>

namespace masav {

int SphPartition::owner(uint32_t cell) const {
  // The last rank whose range starts at or before `cell` (empty ranges are skipped over).
  const auto it = std::upper_bound(begin.begin(), begin.end() - 1, cell);
  return int(it - begin.begin()) - 1;
}

uint32_t partition_bucket_cells(uint64_t cell_count) {
  return uint32_t(
      std::max<uint64_t>(1, (cell_count + kMaxPartitionBuckets - 1) / kMaxPartitionBuckets));
}

SphPartition balance_partition(std::span<const uint64_t> counts, uint32_t bucket_cells,
                               uint32_t cell_count, int ranks) {
  SphPartition p;
  p.begin.assign(size_t(ranks) + 1, cell_count);
  p.begin[0] = 0;
  uint64_t total = 0;
  for (uint64_t c : counts) total += c;
  if (total == 0) {
    for (int r = 1; r < ranks; ++r) p.begin[r] = uint32_t(uint64_t(cell_count) * r / ranks);
    return p;
  }
  uint64_t before = 0;  // particles in the buckets before b
  int r = 1;
  for (size_t b = 0; b < counts.size() && r < ranks; ++b) {
    // Every rank whose share is reached before bucket b starts at b.
    while (r < ranks && before * uint64_t(ranks) >= total * uint64_t(r)) {
      p.begin[r] = uint32_t(std::min<uint64_t>(uint64_t(b) * bucket_cells, cell_count));
      ++r;
    }
    before += counts[b];
  }
  return p;  // ranks whose share is never reached start at the end (own nothing)
}

}  // namespace masav
