#include "engine/cpu/cpu_dfsph_terms.h"

#include <algorithm>

#include "engine/kernels/dfsph_kernels.h"

namespace masav::cpu {
namespace {

using V = sph::V3<double>;

V load3(const double* a, uint32_t i) {
  return V{a[4 * i], a[4 * i + 1], a[4 * i + 2]};
}

}  // namespace

void DfsphTerms::reset(uint32_t n, size_t chunks) {
  valid_ = false;
  chunks_.resize(chunks);
  for (Chunk& c : chunks_) c.size = c.end = 0;  // keeps the arrays: the next build needs as much
  begin_.resize(n);
  count_.resize(n);
  neighbors_.resize(n);
}

// At least `need` terms, and at least twice the old capacity (amortised growth); the terms so
// far move along.
void DfsphTerms::grow(Chunk& c, size_t need) {
  const size_t capacity = std::max(need, 2 * c.capacity);
  std::unique_ptr<DfsphTerm[]> data(new DfsphTerm[capacity]);  // default-initialised: no zeroing
  std::copy(c.data.get(), c.data.get() + c.size, data.get());
  c.data = std::move(data);
  c.capacity = capacity;
}

void DfsphTerms::remember(uint64_t lists_generation, const DfsphLayout<double>& c) {
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

bool DfsphTerms::matches(uint64_t lists_generation, const DfsphLayout<double>& c) const {
  return valid_ && lists_generation == generation_ && c.begin == begin_range_ &&
         c.end == end_range_ && c.h2 == h2_ && c.inv_h == inv_h_ && c.grad == grad_ &&
         c.walls == walls_ && std::equal(c.lo, c.lo + 3, lo_) && std::equal(c.hi, c.hi + 3, hi_);
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
