#pragma once
// The step statistics of the CPU backend's SPH kernels (kSphStat*): gathered per chunk of
// particles and merged once, in chunk order, so that they do not depend on the thread count.
#include <algorithm>
#include <cstdint>
#include <vector>

#include "engine/cpu/cpu_sph_lists.h"

namespace masav::cpu {

// A chunk's statistics, a cache line each: the threads update their chunks' stats particle by
// particle, and neighbouring chunks in one line would pass it between the cores.
struct alignas(64) ChunkStats {
  uint32_t max_candidates = 0, max_neighbors = 0, outside = 0;
  uint32_t overflow = UINT32_MAX, non_finite = UINT32_MAX;  // smallest sorted index
  double max_speed2 = 0, max_accel2 = 0, max_disp2 = 0, max_density = 0;
};

// sph_forces' statistics of particle i: its walk's candidates and overflow, then a non-finite
// acceleration, or the |a|^2 (accel2) of a particle that moves.
inline void add_force_stats(ChunkStats& s, const SphNeighborLists& lists, uint32_t i, bool finite,
                            bool moves, double accel2) {
  s.max_candidates = std::max(s.max_candidates, lists.candidates(i));
  if (lists.overflow(i)) s.overflow = std::min(s.overflow, i);
  if (!finite)
    s.non_finite = std::min(s.non_finite, i);
  else if (moves)
    s.max_accel2 = std::max(s.max_accel2, accel2);
}

// Merges the chunks' statistics into the kernel's stats words.
void merge_sph_stats(uint32_t* words, const std::vector<ChunkStats>& chunks);

}  // namespace masav::cpu
