// DFSPH kernels of the CPU reference: the shared per-particle bodies of
// engine/kernels/dfsph_kernels.h in double precision over the neighbour lists sph_density left
// (cpu_sph_lists.h; rebuilt where they do not match), for the particles of the range computed
// ([begin, end), a rank's own), one contiguous chunk of them per task. Statistics and residual sums
// are gathered per chunk and merged once. By default the solves' pair gradients are found once per
// list (cpu_dfsph_terms.h) and each call sums them in the shared bodies' order, ending in the
// bodies' own tails (dfsph_*_from): the same bits as the bodies, without a square root and a
// division per pair and iteration.
#include <algorithm>
#include <bit>
#include <cmath>
#include <vector>

#include "engine/cpu/cpu_backend.h"
#include "engine/cpu/cpu_sph_rows.h"
#include "engine/kernels/dfsph_kernels.h"

namespace masav::cpu {
namespace {

using V = sph::V3<double>;

V load3(const double* a, size_t i) {
  return V{a[4 * i], a[4 * i + 1], a[4 * i + 2]};
}

// The candidates of sorted particle i: itself, then its neighbour list.
struct ListWalk {
  const SphNeighborLists& lists;
  uint32_t i;
  template <class Visit>
  void operator()(Visit&& visit) const {
    visit(i);
    const uint32_t* list = lists.list(i);
    for (uint32_t k = 0, n = lists.count(i); k < n; ++k) visit(list[k]);
  }
};

// A term's gradient, as sph::dfsph_gradient forms it (0 at r = 0).
V term_gradient(V d, double r2, const DfsphLayout<double>& c) {
  return (r2 > 0 ? sph::dfsph_gradient_scale(r2, c) : 0.0) * d;
}

// Per chunk: the smallest sorted index with a non-finite result or an overflowed walk, the
// largest |v|^2, the residual units. A cache line each: the threads update their chunks' stats
// particle by particle, and neighbouring chunks in one line would pass it between the cores.
struct alignas(64) ChunkStats {
  uint32_t non_finite = UINT32_MAX, overflow = UINT32_MAX;
  double max_speed2 = 0;
  uint64_t residual = 0;
};

void merge(uint32_t* words, const std::vector<ChunkStats>& chunks) {
  for (const ChunkStats& c : chunks) {
    if (c.overflow != UINT32_MAX)
      words[kSphStatOverflow] = std::max(words[kSphStatOverflow], ~c.overflow);
    if (c.non_finite != UINT32_MAX)
      words[kSphStatNonFinite] = std::max(words[kSphStatNonFinite], ~c.non_finite);
    words[kSphStatMaxSpeed2] =
        std::max(words[kSphStatMaxSpeed2], std::bit_cast<uint32_t>(float(c.max_speed2)));
  }
}

}  // namespace

// The terms of each particle: the candidates of ListWalk within h, each pair then its wall
// images -- the walk of sph::dfsph_rate_of, whose gradient factors it keeps.
bool CpuBackend::ensure_dfsph_terms(const double* pos, const DfsphLayout<double>& c,
                                    double* factor) {
  const uint64_t generation = sph_lists_.generation();
  if (dfsph_terms_.matches(generation, c)) return false;
  const size_t chunks = sph_chunks(c.end - c.begin);
  dfsph_terms_.reset(c.n, chunks);
  pool_.run_chunks(c.end - c.begin, chunks, [&](size_t chunk, size_t b, size_t e) {
    // ListWalk's candidates of one particle (itself, then its list): offsets, squared distances
    // and the pair gradients' scales, these computed for the whole list at once.
    std::vector<V> d;
    std::vector<double> r2, scale;
    for (size_t i = c.begin + b; i < c.begin + e; ++i) {
      const uint32_t self = uint32_t(i);
      const V xi = load3(pos, i);
      const sph::WallMirrors<double> m = sph::dfsph_mirrors(xi, c);
      const uint32_t* list = sph_lists_.list(self);
      const uint32_t count = sph_lists_.count(self) + 1;
      auto candidate = [&](uint32_t k) { return k == 0 ? self : list[k - 1]; };
      d.resize(count);
      r2.resize(count);
      scale.resize(count);
      for (uint32_t k = 0; k < count; ++k) {
        d[k] = xi - load3(pos, candidate(k));
        r2[k] = sph::dot(d[k], d[k]);
      }
      gradient_scales(r2.data(), count, c.inv_h, c.grad, scale.data());
      uint32_t neighbors = 0;
      // At most the pair and 7 wall images per candidate within h, itself included.
      dfsph_terms_.begin(chunk, self, 8 * size_t(count));
      for (uint32_t k = 0; k < count; ++k) {
        if (!(r2[k] < c.h2)) continue;
        const uint32_t j = candidate(k);
        ++neighbors;
        // term_gradient(d, r2, c), its scale computed above
        if (j != self) dfsph_terms_.add(chunk, {scale[k] * d[k], j, 0u});
        if (m.axes)
          sph::for_each_wall_image_set(
              xi, load3(pos, j), m, c.h2, [&](V di, double ri2, uint32_t set) {
                dfsph_terms_.add(chunk, {term_gradient(di, ri2, c), j, set});
              });
      }
      dfsph_terms_.end(chunk, self, neighbors);
      if (factor) factor[i] = factor_of_terms(chunk, self);
    }
  });
  dfsph_terms_.remember(generation, c);
  return true;
}

double CpuBackend::factor_of_terms(size_t chunk, uint32_t self) const {
  V sum;
  double sum2;
  dfsph_gradient_sums(dfsph_terms_.terms(chunk, self), dfsph_terms_.count(self), self, sum, sum2);
  return sph::dfsph_factor_from(sum, sum2);
}

void CpuBackend::run_own(const KernelArgs<KernelId::dfsph_factor>& a) {
  auto& [p, items_, positions, cells, cell_start, cell_end, factor, stats, neighbor_rows] = a;
  const char* k = "dfsph_factor";
  const auto c = device_params<double>(p);
  SphListInputs in = sph_list_inputs(p.step, cells, cell_start, cell_end, c.h2, k);
  const double* pos = own(positions.impl(), k).as<double>();
  in.positions = pos;
  double* f = own(factor.impl(), k).as<double>();
  ensure_sph_lists(in);
  const size_t chunks = sph_chunks(c.end - c.begin);  // the range computed, [begin, end)
  std::vector<ChunkStats> st(chunks);
  auto pos_at = [pos](uint32_t j) { return load3(pos, j); };
  // A new build of the terms finds the factors on the way (dfsph_factor_of's sums).
  const bool found = dfsph_terms_on_ && ensure_dfsph_terms(pos, c, f);
  pool_.run_chunks(c.end - c.begin, chunks, [&](size_t chunk, size_t b, size_t e) {
    ChunkStats& s = st[chunk];
    for (size_t i = c.begin + b; i < c.begin + e; ++i) {
      const uint32_t self = uint32_t(i);
      if (!dfsph_terms_on_) {
        f[i] = sph::dfsph_factor_of(self, load3(pos, i), c, ListWalk{sph_lists_, self}, pos_at);
      } else if (!found) {
        f[i] = factor_of_terms(chunk, self);
      }
      if (!std::isfinite(f[i])) s.non_finite = std::min(s.non_finite, self);
      if (sph_lists_.overflow(self)) s.overflow = std::min(s.overflow, self);
    }
  });
  merge(own(stats.impl(), k).as<uint32_t>(), st);
}

void CpuBackend::run_own(const KernelArgs<KernelId::dfsph_rate>& a) {
  auto& [p, items_, positions, velocities, density, factor, cells, cell_start, cell_end, kappa,
         kappa_sum, residual, neighbor_rows] = a;
  const char* k = "dfsph_rate";
  const auto c = device_params<double>(p);
  if (sph::dfsph_stopped(c, own(residual.impl(), k).as<uint32_t>())) return;
  SphListInputs in = sph_list_inputs(p.step, cells, cell_start, cell_end, c.h2, k);
  const double* pos = own(positions.impl(), k).as<double>();
  in.positions = pos;
  const double* vel = own(velocities.impl(), k).as<double>();
  const double* rho = own(density.impl(), k).as<double>();
  const double* f = own(factor.impl(), k).as<double>();
  double* kap = own(kappa.impl(), k).as<double>();
  double* sum = own(kappa_sum.impl(), k).as<double>();
  ensure_sph_lists(in);
  const size_t chunks = sph_chunks(c.end - c.begin);  // the range computed, [begin, end)
  std::vector<ChunkStats> st(chunks);
  auto pos_at = [pos](uint32_t j) { return load3(pos, j); };
  auto vel_at = [vel](uint32_t j) { return load3(vel, j); };
  if (dfsph_terms_on_) ensure_dfsph_terms(pos, c);
  auto rate_of_terms = [&](size_t chunk, uint32_t self) {
    const double div = dfsph_divergence(dfsph_terms_.terms(chunk, self), dfsph_terms_.count(self),
                                        self, load3(vel, self), vel);
    return sph::dfsph_rate_from(div, dfsph_terms_.neighbors(self), rho[self], f[self], c);
  };
  pool_.run_chunks(c.end - c.begin, chunks, [&](size_t chunk, size_t b, size_t e) {
    ChunkStats& s = st[chunk];
    for (size_t i = c.begin + b; i < c.begin + e; ++i) {
      const uint32_t self = uint32_t(i);
      const auto r = dfsph_terms_on_
                         ? rate_of_terms(chunk, self)
                         : sph::dfsph_rate_of(self, load3(pos, i), load3(vel, i), rho[i], f[i], c,
                                              ListWalk{sph_lists_, self}, pos_at, vel_at);
      kap[i] = r.kappa;
      sum[i] = sph::dfsph_kappa_sum(sum[i], r.kappa, c);
      if (pos[4 * i + 3] > 0) s.residual += sph::dfsph_residual_units(r.residual);
    }
  });
  uint64_t total = 0;
  for (const ChunkStats& s : st) total += s.residual;
  uint32_t* words = own(residual.impl(), k).as<uint32_t>() + 2 * size_t(p.slot);
  const uint64_t now = (uint64_t(words[1]) << 32 | words[0]) + total;
  words[0] = uint32_t(now);
  words[1] = uint32_t(now >> 32);
}

void CpuBackend::run_own(const KernelArgs<KernelId::dfsph_correct>& a) {
  auto& [p, items_, positions, kappa, cells, cell_start, cell_end, velocities, stats, residual,
         neighbor_rows] = a;
  const char* k = "dfsph_correct";
  const auto c = device_params<double>(p);
  if (residual && sph::dfsph_stopped(c, own(residual->impl(), k).as<uint32_t>())) return;
  SphListInputs in = sph_list_inputs(p.step, cells, cell_start, cell_end, c.h2, k);
  const double* pos = own(positions.impl(), k).as<double>();
  in.positions = pos;
  const double* kap = own(kappa.impl(), k).as<double>();
  double* vel = own(velocities.impl(), k).as<double>();
  ensure_sph_lists(in);
  const size_t chunks = sph_chunks(c.end - c.begin);  // the range computed, [begin, end)
  std::vector<ChunkStats> st(chunks);
  auto pos_at = [pos](uint32_t j) { return load3(pos, j); };
  auto kappa_at = [kap](uint32_t j) { return kap[j]; };
  if (dfsph_terms_on_) ensure_dfsph_terms(pos, c);
  auto correction_of_terms = [&](size_t chunk, uint32_t self) {
    return sph::dfsph_correction_from(
        dfsph_kappa_gradient_sum(dfsph_terms_.terms(chunk, self), dfsph_terms_.count(self), self,
                                 kap[self], kap),
        c);
  };
  pool_.run_chunks(c.end - c.begin, chunks, [&](size_t chunk, size_t b, size_t e) {
    ChunkStats& s = st[chunk];
    for (size_t i = c.begin + b; i < c.begin + e; ++i) {
      const uint32_t self = uint32_t(i);
      const double w = pos[4 * i + 3];
      if (!(w > 0)) continue;  // pinned: never moves
      const V dv = dfsph_terms_on_
                       ? correction_of_terms(chunk, self)
                       : sph::dfsph_correction_of(self, load3(pos, i), kap[i], c,
                                                  ListWalk{sph_lists_, self}, pos_at, kappa_at);
      const V v = load3(vel, i) + w * dv;
      vel[4 * i] = v.x;
      vel[4 * i + 1] = v.y;
      vel[4 * i + 2] = v.z;
      if (!(std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z)))
        s.non_finite = std::min(s.non_finite, self);
      else
        s.max_speed2 = std::max(s.max_speed2, sph::dot(v, v));
    }
  });
  merge(own(stats.impl(), k).as<uint32_t>(), st);
}

}  // namespace masav::cpu
