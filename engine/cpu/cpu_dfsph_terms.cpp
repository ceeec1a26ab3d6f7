#include "engine/cpu/cpu_dfsph_terms.h"

#include <algorithm>

#include "engine/kernels/dfsph_kernels.h"

namespace masav::cpu {
namespace {

using V = sph::V3<double>;

V load3(const double* a, uint32_t i) {
  return V{a[4 * i], a[4 * i + 1], a[4 * i + 2]};
}

// At least `need`, and at least twice the old capacity (amortised growth).
size_t grown(size_t capacity, size_t need) {
  return std::max(need, 2 * capacity);
}

// A copy of the first `size` of `old` in a new array of `capacity` (default-initialised beyond:
// no zeroing of what the build overwrites), then `slack` zeros.
template <class T>
std::unique_ptr<T[]> moved(const std::unique_ptr<T[]>& old, size_t size, size_t capacity,
                           size_t slack = 0) {
  std::unique_ptr<T[]> data(new T[capacity + slack]);
  if (size) std::copy(old.get(), old.get() + size, data.get());
  std::fill(data.get() + capacity, data.get() + capacity + slack, T{});
  return data;
}

}  // namespace

void DfsphTermsIndex::reset_index(uint32_t n) {
  valid_ = false;
  begin_.resize(n);
  count_.resize(n);
  neighbors_.resize(n);
}

void DfsphTermsIndex::remember(uint64_t lists_generation, const DfsphLayout<double>& c) {
  generation_ = lists_generation;
  begin_range_ = c.begin;
  end_range_ = c.end;
  h2_ = c.h2;
  inv_h_ = c.inv_h;
  grad_ = c.grad;
  walls_ = c.walls;
  std::copy(c.lo, c.lo + 3, lo_);
  std::copy(c.hi, c.hi + 3, hi_);
  valid_ = true;
}

bool DfsphTermsIndex::matches(uint64_t lists_generation, const DfsphLayout<double>& c) const {
  return valid_ && lists_generation == generation_ && c.begin == begin_range_ &&
         c.end == end_range_ && c.h2 == h2_ && c.inv_h == inv_h_ && c.grad == grad_ &&
         c.walls == walls_ && std::equal(c.lo, c.lo + 3, lo_) && std::equal(c.hi, c.hi + 3, hi_);
}

// Both keep their arrays: the next build needs as much.
void DfsphTerms::reset(uint32_t n, size_t chunks) {
  reset_index(n);
  chunks_.resize(chunks);
  for (Chunk& c : chunks_) c.size = c.end = 0;
}
void DfsphTerms32::reset(uint32_t n, size_t chunks) {
  reset_index(n);
  factor_.resize(n);
  chunks_.resize(chunks);
  for (Chunk& c : chunks_) c.size = c.end = 0;
}

void DfsphTerms::Chunk::grow(size_t need) {
  const size_t to = grown(capacity, need);
  data = moved(data, size, to);
  capacity = to;
}
void DfsphTerms32::Chunk::grow(size_t need) {
  const size_t to = grown(capacity, need);
  gx = moved(gx, size, to, kSlack);
  gy = moved(gy, size, to, kSlack);
  gz = moved(gz, size, to, kSlack);
  js = moved(js, size, to, kSlack);
  capacity = to;
}

void dfsph_gradient_sums(const DfsphTerm* t, uint32_t count, uint32_t self, V& sum, double& sum2) {
  sum = V{0, 0, 0};
  sum2 = 0;
  for (uint32_t k = 0; k < count; ++k) {
    const V g = t[k].gradient;
    if (t[k].j == self) {
      sum = sum + 2.0 * g;
    } else {
      sum = sum + g;
      sum2 += sph::dot(g, g);
    }
  }
}

double dfsph_divergence(const DfsphTerm* t, uint32_t count, uint32_t self, V vi,
                        const double* vel) {
  double div = 0;
  for (uint32_t k = 0; k < count; ++k) {
    const V vj = t[k].j == self ? vi : load3(vel, t[k].j);
    div += sph::dot(t[k].gradient, vi - (t[k].set == 0 ? vj : sph::mirror_velocity(vj, t[k].set)));
  }
  return div;
}

V dfsph_kappa_gradient_sum(const DfsphTerm* t, uint32_t count, uint32_t self, double kappa_i,
                           const double* kappa) {
  V acc{0, 0, 0};
  for (uint32_t k = 0; k < count; ++k) {
    const uint32_t j = t[k].j;
    acc = acc + (kappa_i + (j == self ? kappa_i : kappa[j])) * t[k].gradient;
  }
  return acc;
}

}  // namespace masav::cpu
