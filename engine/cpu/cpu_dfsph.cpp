// DFSPH kernels of the CPU reference: the shared per-particle bodies of
// engine/kernels/dfsph_kernels.h in double precision over the neighbour lists sph_density left
// (cpu_sph_lists.h; rebuilt where they do not match), for the particles of the range computed
// ([begin, end), a rank's own), one contiguous chunk of them per task. Statistics and residual sums
// are gathered per chunk and merged once. By default the solves' pair gradients are found once per
// list (cpu_dfsph_terms.h) and each call sums them in the shared bodies' order, ending in the
// bodies' own tails (dfsph_*_from): the same bits as the bodies, without a square root and a
// division per pair and iteration. With CpuTuning::sph_precision = fp32 the kept gradients are
// rounded to fp32 (DfsphTerms32, half the bytes) and the solves sum them over fp32 copies of the
// velocities and kappas, 16 terms at a time (SphSimdKernels, the same bits with every
// instruction set), ending in the same double tails; the factor and everything outside the sums
// stays in double.
#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <vector>

#include "engine/cpu/cpu_backend.h"
#include "engine/core/error.h"
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

// A particle's factor from its kept terms (dfsph_factor_of's sums).
double factor_of_terms(const DfsphTerms& terms, size_t chunk, uint32_t self) {
  V sum;
  double sum2;
  dfsph_gradient_sums(terms.terms(chunk, self), terms.count(self), self, sum, sum2);
  return sph::dfsph_factor_from(sum, sum2);
}

}  // namespace

const float* CpuBackend::fp32_rows(std::vector<float>& out, const double* in, uint32_t n,
                                   size_t width) {
  out.resize(width * std::max<size_t>(n, 1));
  float* o = out.data();
  pool_.parallel_for(width * n, 8192, [&](size_t b, size_t e) {
    for (size_t k = b; k < e; ++k) o[k] = float(in[k]);
  });
  return o;
}

// The terms of each particle: the candidates of ListWalk within h, each pair then its wall
// images -- the walk of sph::dfsph_rate_of, whose gradient factors it keeps.
bool CpuBackend::ensure_dfsph_terms(DfsphTerms& terms, const double* pos,
                                    const DfsphLayout<double>& c, double* factor) {
  const uint64_t generation = sph_lists_.generation();
  if (terms.matches(generation, c)) return false;
  const size_t chunks = sph_chunks(c.end - c.begin);
  terms.reset(c.n, chunks);
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
      terms.begin(chunk, self, 8 * size_t(count));
      for (uint32_t k = 0; k < count; ++k) {
        if (!(r2[k] < c.h2)) continue;
        const uint32_t j = candidate(k);
        ++neighbors;
        // term_gradient(d, r2, c), its scale computed above
        if (j != self) terms.add(chunk, scale[k] * d[k], j, 0u);
        if (m.axes)
          sph::for_each_wall_image_set(
              xi, load3(pos, j), m, c.h2, [&](V di, double ri2, uint32_t set) {
                terms.add(chunk, term_gradient(di, ri2, c), j, set);
              });
      }
      terms.end(chunk, self, neighbors);
      if (factor) factor[i] = factor_of_terms(terms, chunk, self);
    }
  });
  terms.remember(generation, c);
  return true;
}

// The fp32 path's terms: each listed neighbour's pair term (the lists hold exactly the fp32
// candidates within h), 16 at a time in fp32 from fp32 positions, then near a wall the images
// of the particle and of each neighbour, set by set; the factor from the same sums.
bool CpuBackend::ensure_dfsph_terms32(const double* pos, const DfsphParams& p, double* factor) {
  const auto c = device_params<double>(p);
  const auto c32 = device_params<float>(p);
  if (c.n >= DfsphTerms32::kMaxParticles)
    throw Error("cpu", "dfsph_factor",
                fmt::format("{} particles with cpu.sph_precision = fp32, whose DFSPH terms hold "
                            "at most {}",
                            c.n, DfsphTerms32::kMaxParticles - 1),
                "use cpu.sph_precision = fp64, or more ranks");
  DfsphTerms32& terms = dfsph_terms32_;
  const uint64_t generation = sph_lists_.generation();
  if (terms.matches(generation, c)) return false;
  // Positions in fp32 rows of 4 (the fourth unread), for every particle a list can name.
  const float* xyz = fp32_rows(dfsph_xyz32_, pos, c.n, 4);
  const SimdDfsphConstants sc{c32.inv_h, c32.grad};
  const size_t chunks = sph_chunks(c.end - c.begin);
  terms.reset(c.n, chunks);
  pool_.run_chunks(c.end - c.begin, chunks, [&](size_t chunk, size_t b, size_t e) {
    using F = sph::V3<float>;
    for (size_t i = c.begin + b; i < c.begin + e; ++i) {
      const uint32_t self = uint32_t(i);
      const F xi{xyz[4 * i], xyz[4 * i + 1], xyz[4 * i + 2]};
      const sph::WallMirrors<float> m = sph::dfsph_mirrors(xi, c32);
      const uint32_t* list = sph_lists_.list(self);
      const uint32_t count = sph_lists_.count(self);
      // The pairs, 7 images of each candidate at most (itself included), the SIMD writes' room.
      terms.begin(chunk, self, count + 7 * (size_t(count) + 1) + DfsphTerms32::kSlack);
      float sum[3], sum2;
      sph_simd_->dfsph_pair_terms(xyz, list, count, xi.x, xi.y, xi.z, sc, terms.next(chunk), sum,
                                  &sum2);
      terms.advance(chunk, count);
      if (m.axes) {
        // Its own images (sph::dfsph_factor_of counts them twice in the sum, not in the
        // squares), then its neighbours'.
        sph::for_each_wall_image_set(xi, xi, m, c32.h2, [&](F d, float r2, uint32_t set) {
          const F g = sph::dfsph_gradient(d, r2, c32);
          terms.add(chunk, V{g.x, g.y, g.z}, self, set);
          sum[0] += 2.0f * g.x;
          sum[1] += 2.0f * g.y;
          sum[2] += 2.0f * g.z;
        });
        terms.advance(chunk, sph_simd_->dfsph_image_terms(xyz, list, count, xi.x, xi.y, xi.z,
                                                          m.axes, m.plane, c32.h2, sc,
                                                          terms.next(chunk), sum, &sum2));
      }
      terms.end(chunk, self, count + 1);
      terms.set_factor(self, sph::dfsph_factor_from(V{sum[0], sum[1], sum[2]}, double(sum2)));
      if (factor) factor[i] = terms.factor(self);
    }
  });
  terms.remember(generation, c);
  return true;
}

void CpuBackend::ensure_solve_terms(const double* pos, const DfsphParams& p) {
  if (sph_in_fp32())
    ensure_dfsph_terms32(pos, p);
  else if (dfsph_terms_on_)
    ensure_dfsph_terms(dfsph_terms_, pos, device_params<double>(p));
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
  const bool fp32 = sph_in_fp32();
  const bool found = fp32              ? ensure_dfsph_terms32(pos, p, f)
                     : dfsph_terms_on_ ? ensure_dfsph_terms(dfsph_terms_, pos, c, f)
                                       : false;
  pool_.run_chunks(c.end - c.begin, chunks, [&](size_t chunk, size_t b, size_t e) {
    ChunkStats& s = st[chunk];
    for (size_t i = c.begin + b; i < c.begin + e; ++i) {
      const uint32_t self = uint32_t(i);
      if (!found) {
        f[i] = fp32              ? dfsph_terms32_.factor(self)
               : dfsph_terms_on_ ? factor_of_terms(dfsph_terms_, chunk, self)
                                 : sph::dfsph_factor_of(self, load3(pos, i), c,
                                                        ListWalk{sph_lists_, self}, pos_at);
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
  const bool fp32 = sph_in_fp32();
  ensure_solve_terms(pos, p);
  const float* vel32 = fp32 ? fp32_rows(dfsph_vel32_, vel, c.n, 4) : nullptr;
  auto rate_of_terms = [&](size_t chunk, uint32_t self) {
    if (fp32) {
      const float* vi = vel32 + 4 * size_t(self);
      const float div = sph_simd_->dfsph_divergence(dfsph_terms32_.terms(chunk, self), vi[0],
                                                    vi[1], vi[2], vel32);
      return sph::dfsph_rate_from(double(div), dfsph_terms32_.neighbors(self), rho[self], f[self],
                                  c);
    }
    const double div = dfsph_divergence(dfsph_terms_.terms(chunk, self), dfsph_terms_.count(self),
                                        self, load3(vel, self), vel);
    return sph::dfsph_rate_from(div, dfsph_terms_.neighbors(self), rho[self], f[self], c);
  };
  pool_.run_chunks(c.end - c.begin, chunks, [&](size_t chunk, size_t b, size_t e) {
    ChunkStats& s = st[chunk];
    for (size_t i = c.begin + b; i < c.begin + e; ++i) {
      const uint32_t self = uint32_t(i);
      const auto r = fp32 || dfsph_terms_on_
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
  const bool fp32 = sph_in_fp32();
  ensure_solve_terms(pos, p);
  const float* kap32 = fp32 ? fp32_rows(dfsph_kappa32_, kap, c.n, 1) : nullptr;
  auto correction_of_terms = [&](size_t chunk, uint32_t self) {
    if (fp32) {
      float acc[3];
      sph_simd_->dfsph_kappa_gradient(dfsph_terms32_.terms(chunk, self), kap32[self], kap32, acc);
      return sph::dfsph_correction_from(V{acc[0], acc[1], acc[2]}, c);
    }
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
      const V dv = fp32 || dfsph_terms_on_
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
