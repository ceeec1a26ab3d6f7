#pragma once
// Neighbour lists of the CPU reference's SPH kernels. sph_density finds every particle's
// neighbours (within h, itself excluded) and keeps them here; sph_forces, called next on the
// same positions and grid, reads them instead of testing every candidate of the 27 cells again
// (that test was a quarter of a step). A list is a pure function of the inputs recorded in
// SphListKey, and the key is compared by content, so a list is reused only where a fresh walk
// would find exactly the same neighbours in the same order.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "engine/cpu/thread_pool.h"
#include "engine/kernels/sph_kernel_params.h"

namespace masav::cpu {

// sph_density's reach masks (SphReach) as the list build uses them: recorded (the candidates
// within reach2, itself included, as masks in `rows`) or walked (only their bits are tested).
struct SphListReach {
  SphReach mode = SphReach::none;
  double reach2 = 0;
  uint32_t* rows = nullptr;  // kSphRowMaskWords n words
};

// What a neighbour walk reads: sorted positions (x, y, z, w), each particle's cell, the cell
// ranges, the grid's dims, h^2 and the candidate cap; and the particles whose lists are made,
// [first, end) of the n.
struct SphListInputs {
  const double* positions;
  const uint32_t* cells;
  const uint32_t* cell_start;
  const uint32_t* cell_end;
  uint64_t cell_count;
  uint32_t n;
  uint32_t first, end;
  uint32_t dims[3];
  double h2;
  uint32_t max_candidates;
  bool fp32 = false;  // distances tested in fp32 (CpuTuning::sph_precision): lists of their own
};

class SphNeighborLists {
 public:
  // Forgets the old lists and sizes for `chunks` chunks of `n` particles.
  void reset(uint32_t n, size_t chunks);
  // Records the inputs the lists now being built belong to (copies them).
  void remember(const SphListInputs& in);
  // True if the lists were built from inputs equal to `in` (for the particles of its range, or a
  // range around it: a rank's forces run over parts of the range its density pass listed).
  bool matches(const SphListInputs& in, ThreadPool& pool) const;
  // Counts the builds (reset): what is derived from the lists names the build it came from.
  uint64_t generation() const { return generation_; }

  // Chunk `chunk` appends particle i's list (called for i in increasing order).
  void append(size_t chunk, uint32_t i, const uint32_t* neighbors, uint32_t count,
              uint32_t candidates, bool overflow);

  const uint32_t* list(uint32_t i) const { return index_[chunk_of_[i]].data() + begin_[i]; }
  uint32_t count(uint32_t i) const { return count_[i]; }
  uint32_t candidates(uint32_t i) const { return candidates_[i]; }
  bool overflow(uint32_t i) const { return overflow_[i] != 0; }

 private:
  bool valid_ = false;
  uint64_t generation_ = 0;
  uint32_t n_ = 0, first_ = 0, end_ = 0, max_candidates_ = 0, dims_[3] = {0, 0, 0};
  double h2_ = 0;
  bool fp32_ = false;
  std::vector<double> positions_;  // x, y, z, w per particle, compared bit for bit
  std::vector<uint32_t> cells_, cell_start_, cell_end_;

  std::vector<std::vector<uint32_t>> index_;  // per chunk: its particles' lists, concatenated
  std::vector<size_t> begin_;       // where particle i's list starts in its chunk's index_
  std::vector<uint32_t> chunk_of_;  // the chunk that listed particle i
  std::vector<uint32_t> count_, candidates_;
  std::vector<uint8_t> overflow_;
};

}  // namespace masav::cpu
