#pragma once
// The pair terms of the CPU reference's DFSPH kernels, kept between calls. Every dfsph_rate and
// dfsph_correct of a solve walks the same neighbours at the same positions, and each pair's
// spiky gradient m grad W_ij = s d_ij (s: a square root and a division,
// sph::dfsph_gradient_scale; d the offset to the neighbour or its image) depends on the positions
// alone; so the gradients are found once per neighbour list, with the bodies' own operations
// (the same bits), and each iteration reads them instead of the neighbours' positions. A
// particle's terms are the ones the shared bodies
// (engine/kernels/dfsph_kernels.h) visit, in the order they visit them -- itself, then its list;
// for each candidate within h the pair, then its wall images by mirror set -- so the sums over
// them are the same sums, bit for bit.
#include <cassert>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "engine/cpu/cpu_sph_simd.h"
#include "engine/kernels/dfsph_params.h"
#include "engine/kernels/sph_kernels.h"

namespace masav::cpu {

// 32 bytes (about 60 per particle at h = 2 dx).
struct DfsphTerm {
  sph::V3<double> gradient;  // m grad_i W (sph::dfsph_gradient of x_i - x_j or of its image)
  uint32_t j;                // sorted neighbour; j == i: one of the particle's own images
  uint32_t set;  // 0: the pair; else the image's mirror set (sph::for_each_wall_image_set)
};

// What a set of kept terms was built for, and where each particle's terms are in its chunk.
class DfsphTermsIndex {
 public:
  // Records what the terms now being built belong to: the neighbour lists' build (their
  // generation), the particles computed (their chunks index the terms) and the layout's
  // gradient and walls.
  void remember(uint64_t lists_generation, const DfsphLayout<double>& c);
  // True if the terms were built for lists `lists_generation` with the same range, gradient and
  // walls.
  bool matches(uint64_t lists_generation, const DfsphLayout<double>& c) const;
  uint32_t count(uint32_t i) const { return count_[i]; }
  uint32_t neighbors(uint32_t i) const { return neighbors_[i]; }

 protected:
  void reset_index(uint32_t n);
  // Starts particle i's terms in chunk c (a store's Chunk: size, capacity, end, grow(need)) with
  // room for `most`.
  template <class Chunk>
  void start(Chunk& c, uint32_t i, size_t most) {
    if (c.size + most > c.capacity) c.grow(c.size + most);
    c.end = c.size + most;
    begin_[i] = c.size;
  }
  void finish(uint32_t i, size_t at, uint32_t neighbors) {
    count_[i] = uint32_t(at - begin_[i]);
    neighbors_[i] = neighbors;
  }
  std::vector<size_t> begin_;

 private:
  bool valid_ = false;
  uint64_t generation_ = 0;
  uint32_t begin_range_ = 0, end_range_ = 0;
  double h2_ = 0, inv_h_ = 0, grad_ = 0, lo_[3] = {0, 0, 0}, hi_[3] = {0, 0, 0};
  uint32_t walls_ = 0;
  std::vector<uint32_t> count_, neighbors_;
};

// Every particle's terms, per chunk of particles (a task's), concatenated. A chunk starts
// particle i's terms (called for i in increasing order) with room for at most `most` of them,
// then adds them without a capacity test (the build's inner loop; a std::vector's push_back
// there took 7% of a DFSPH step), then ends them with `neighbors`, the candidates within h
// (itself included).
class DfsphTerms : public DfsphTermsIndex {
 public:
  // Forgets the old terms and sizes for `chunks` chunks of `n` particles.
  void reset(uint32_t n, size_t chunks);
  void begin(size_t chunk, uint32_t i, size_t most) { start(chunks_[chunk], i, most); }
  void add(size_t chunk, sph::V3<double> g, uint32_t j, uint32_t set) {
    Chunk& c = chunks_[chunk];
    assert(c.size < c.end);
    c.data[c.size++] = DfsphTerm{g, j, set};
  }
  void end(size_t chunk, uint32_t i, uint32_t neighbors) {
    finish(i, chunks_[chunk].size, neighbors);
  }
  const DfsphTerm* terms(size_t chunk, uint32_t i) const {
    return chunks_[chunk].data.get() + begin_[i];
  }

 private:
  struct Chunk {
    std::unique_ptr<DfsphTerm[]> data;
    size_t size = 0, capacity = 0, end = 0;
    void grow(size_t need);
  };
  std::vector<Chunk> chunks_;
};

// The fp32 path's terms (CpuTuning::sph_precision = fp32): the same gradients rounded to fp32,
// as arrays for the SIMD solves (SimdDfsphTerms), the mirror set in the top 3 bits of j:
// 16 bytes a term, read 16 at a time, with 16 readable entries past each chunk's end.
class DfsphTerms32 : public DfsphTermsIndex {
 public:
  static constexpr uint32_t kSetShift = 29;
  static constexpr uint32_t kMaxParticles = 1u << kSetShift;  // j below it
  static constexpr size_t kSlack = 16;

  void reset(uint32_t n, size_t chunks);
  void begin(size_t chunk, uint32_t i, size_t most) { start(chunks_[chunk], i, most); }
  void add(size_t chunk, sph::V3<double> g, uint32_t j, uint32_t set) {
    Chunk& c = chunks_[chunk];
    assert(c.size < c.end);
    c.gx[c.size] = float(g.x);
    c.gy[c.size] = float(g.y);
    c.gz[c.size] = float(g.z);
    c.js[c.size++] = j | set << kSetShift;
  }
  // Where the next terms go, for SphSimdKernels::dfsph_pair_terms (begin's `most` must leave
  // room for its writes past them), then how many it wrote.
  SimdDfsphOut next(size_t chunk) {
    Chunk& c = chunks_[chunk];
    return {c.gx.get() + c.size, c.gy.get() + c.size, c.gz.get() + c.size, c.js.get() + c.size};
  }
  void advance(size_t chunk, size_t written) {
    Chunk& c = chunks_[chunk];
    c.size += written;
    assert(c.size <= c.end);
  }
  void end(size_t chunk, uint32_t i, uint32_t neighbors) {
    finish(i, chunks_[chunk].size, neighbors);
  }
  SimdDfsphTerms terms(size_t chunk, uint32_t i) const {
    const Chunk& c = chunks_[chunk];
    const size_t b = begin_[i];
    return {c.gx.get() + b, c.gy.get() + b, c.gz.get() + b, c.js.get() + b, count(i)};
  }
  // Particle i's factor, found from the terms' fp32 sums as they were built (the build's order,
  // which a later sum over the kept terms would not repeat).
  void set_factor(uint32_t i, double f) { factor_[i] = f; }
  double factor(uint32_t i) const { return factor_[i]; }

 private:
  struct Chunk {
    std::unique_ptr<float[]> gx, gy, gz;
    std::unique_ptr<uint32_t[]> js;
    size_t size = 0, capacity = 0, end = 0;
    void grow(size_t need);
  };
  std::vector<Chunk> chunks_;
  std::vector<double> factor_;
};

// The sums of the shared bodies over particle `self`'s `count` terms `t`, from sorted
// velocities (x, y, z, w rows) and kappas: dfsph_factor_of's gradient sum (own images twice)
// and sum of squares ...
void dfsph_gradient_sums(const DfsphTerm* t, uint32_t count, uint32_t self, sph::V3<double>& sum,
                         double& sum2);
// ... dfsph_rate_of's density change rate at velocity vi (an image moves with the mirrored
// velocity) ...
double dfsph_divergence(const DfsphTerm* t, uint32_t count, uint32_t self, sph::V3<double> vi,
                        const double* vel);
// ... and dfsph_correction_of's sum of (k_i + k_j) m grad W_ij (k_i + k_i for an own image).
sph::V3<double> dfsph_kappa_gradient_sum(const DfsphTerm* t, uint32_t count, uint32_t self,
                                         double kappa_i, const double* kappa);

}  // namespace masav::cpu
