#pragma once
// The step statistics of the CPU backend's SPH kernels (kSphStat*): gathered per chunk of
// particles and merged once, in chunk order, so that they do not depend on the thread count.
#include <cstdint>
#include <vector>

namespace masav::cpu {

// A chunk's statistics, a cache line each: the threads update their chunks' stats particle by
// particle, and neighbouring chunks in one line would pass it between the cores.
struct alignas(64) ChunkStats {
  uint32_t max_candidates = 0, max_neighbors = 0, outside = 0;
  uint32_t overflow = UINT32_MAX, non_finite = UINT32_MAX;  // smallest sorted index
  double max_speed2 = 0, max_accel2 = 0, max_disp2 = 0, max_density = 0;
};

// Merges the chunks' statistics into the kernel's stats words.
void merge_sph_stats(uint32_t* words, const std::vector<ChunkStats>& chunks);

}  // namespace masav::cpu
