// SPH kernels of the CPU reference: the shared per-particle bodies of
// engine/kernels/sph_kernels.h in double precision, one contiguous chunk of sorted particles per
// task. Statistics are gathered per chunk and merged once, in chunk order. sph_density finds the
// neighbour lists (cpu_sph_lists.h) that sph_forces then reuses; the candidate test runs on
// structure-of-arrays positions (cpu_sph_rows.h). The neighbour row masks, the GPU backends'
// form of those lists, are written from the lists when asked for and never read here.
#include <algorithm>
#include <bit>
#include <cmath>
#include <vector>

#include "engine/cpu/cpu_backend.h"
#include "engine/cpu/cpu_sph_rows.h"
#include "engine/cpu/cpu_sph_stats.h"
#include "engine/cpu/cpu_sph_simd.h"
#include "engine/kernels/sph_integrate_body.h"

namespace masav::cpu {
namespace {

using V = sph::V3<double>;

uint32_t float_bits(double v) {
  return std::bit_cast<uint32_t>(float(v));
}

size_t chunk_count(const ThreadPool& pool, size_t n, size_t grain) {
  if (n == 0) return 0;
  return std::min<size_t>(std::max<size_t>(1, n / grain), size_t(pool.size()) * 8);
}

V load3(const double* a, size_t i) {
  return V{a[4 * i], a[4 * i + 1], a[4 * i + 2]};
}
void store3(double* a, size_t i, V v, double w) {
  a[4 * i] = v.x;
  a[4 * i + 1] = v.y;
  a[4 * i + 2] = v.z;
  a[4 * i + 3] = w;
}

// The density the wall images (sph::WallMirrors) of particle i and of its `count` neighbours
// `list` add at i.
double wall_images_density(const SphStepLayout<double>& c, const double* pos, uint32_t i,
                           const uint32_t* list, uint32_t count) {
  if (!c.walls) return 0.0;
  const V xi = load3(pos, i);
  const auto mirrors = sph::wall_mirrors(xi, c);
  if (!mirrors.axes) return 0.0;
  double sum = 0.0;
  for (uint32_t n = 0; n < count; ++n)
    sum += sph::wall_image_density(xi, load3(pos, list[n]), mirrors, c);
  return c.density * sum + sph::own_image_density(xi, mirrors, c);
}
bool finite3(V v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// The spiky density terms (sph::density_term: wcsph, dfsph) over a neighbour list's squared
// distances.
double spiky_density_sum(const double* r2, uint32_t count, const SphStepLayout<double>& c) {
  double sum = 0.0;
  for (uint32_t k = 0; k < count; ++k) sum += sph::density_term(r2[k], c);
  return sum;
}

// Positions as three contiguous arrays (the row loops vectorise over them), in T, with a
// vector's slack at the end that the fp32 loops read (and ignore).
template <class T>
struct Soa {
  std::vector<T> x, y, z;
};
template <class T>
const Soa<T>& soa_positions(ThreadPool& pool, const double* pos, size_t n) {
  static thread_local Soa<T> mine;
  Soa<T>& s = mine;  // the caller's copy: worker threads must not name their own thread_local
  for (std::vector<T>* a : {&s.x, &s.y, &s.z}) {
    a->resize(n + 16);
    std::fill(a->begin() + std::ptrdiff_t(n), a->end(), T(0));
  }
  pool.parallel_for(n, 8192, [&](size_t b, size_t e) {
    for (size_t i = b; i < e; ++i) {
      s.x[i] = T(pos[4 * i]);
      s.y[i] = T(pos[4 * i + 1]);
      s.z[i] = T(pos[4 * i + 2]);
    }
  });
  return s;
}

// wall_images_density in fp32: the neighbours' images in the SIMD loop, then the particle's own.
float fp32_wall_images_density(const SphSimdKernels& k, const SphStepLayout<float>& c,
                               const SimdPairConstants& simd, const Soa<float>& xyz, uint32_t i,
                               const uint32_t* list, uint32_t count) {
  if (!c.walls) return 0.0f;
  const sph::V3<float> xi{xyz.x[i], xyz.y[i], xyz.z[i]};
  const auto mirrors = sph::wall_mirrors(xi, c);
  if (!mirrors.axes) return 0.0f;
  const float sum = k.image_density_sum(xyz.x.data(), xyz.y.data(), xyz.z.data(), list, count,
                                        xi.x, xi.y, xi.z, mirrors.axes, mirrors.plane, simd);
  return c.density * sum + sph::own_image_density(xi, mirrors, c);
}

// Particle i's row masks (sph::RowMasks) from its list of the candidates within a radius (h for
// the neighbour rows, the reach radius for the reach masks) in walk order -- ascending within a
// row, rows in walk order -- without the particle itself, which the masks include.
void write_row_masks(const SphListInputs& in, uint32_t i, const uint32_t* list, uint32_t count,
                     uint32_t* neighbor_rows) {
  const sph::RowMasks<uint32_t> masks = sph::row_masks(neighbor_rows, i, in.n);
  uint32_t k = 0;
  bool overflow = false;
  sph::walk_rows(in.cells[i], in.dims, in.cell_start, in.cell_end, in.max_candidates, overflow,
                 [&](uint32_t row, uint32_t first, uint32_t last) {
                   uint64_t bits = 0;
                   for (; k < count && list[k] >= first && list[k] < last; ++k)
                     bits |= uint64_t(1) << ((list[k] - first) & (kSphRowMaskBits - 1));
                   if (i >= first && i < last)
                     bits |= uint64_t(1) << ((i - first) & (kSphRowMaskBits - 1));
                   sph::store_row_mask(masks, row, sph::row_fits_mask(first, last) ? bits : 0);
                 });
}

// Keeps the entries of (index, r2) with r2 < h2, in order; returns how many.
template <class T>
uint32_t keep_within(uint32_t* index, T* r2, uint32_t count, T h2) {
  uint32_t kept = 0;
  for (uint32_t k = 0; k < count; ++k) {
    index[kept] = index[k];
    r2[kept] = r2[k];
    kept += r2[k] < h2 ? 1u : 0u;
  }
  return kept;
}

}  // namespace

void merge_sph_stats(uint32_t* words, const std::vector<ChunkStats>& chunks) {
  for (const ChunkStats& c : chunks) {
    words[kSphStatMaxCandidates] = std::max(words[kSphStatMaxCandidates], c.max_candidates);
    words[kSphStatMaxNeighbors] = std::max(words[kSphStatMaxNeighbors], c.max_neighbors);
    words[kSphStatOutside] += c.outside;
    if (c.overflow != UINT32_MAX)
      words[kSphStatOverflow] = std::max(words[kSphStatOverflow], ~c.overflow);
    if (c.non_finite != UINT32_MAX)
      words[kSphStatNonFinite] = std::max(words[kSphStatNonFinite], ~c.non_finite);
    // Non-negative floats order like their bit patterns.
    words[kSphStatMaxSpeed2] = std::max(words[kSphStatMaxSpeed2], float_bits(c.max_speed2));
    words[kSphStatMaxAccel2] = std::max(words[kSphStatMaxAccel2], float_bits(c.max_accel2));
    words[kSphStatMaxDisp2] = std::max(words[kSphStatMaxDisp2], float_bits(c.max_disp2));
    words[kSphStatMaxDensity] = std::max(words[kSphStatMaxDensity], float_bits(c.max_density));
  }
}

SphListInputs CpuBackend::sph_list_inputs(const SphStepParams& p, const Buffer<uint32_t>& cells,
                                          const Buffer<uint32_t>& cell_start,
                                          const Buffer<uint32_t>& cell_end, double h2,
                                          const char* kernel) const {
  SphListInputs in{};
  in.cells = own(cells.impl(), kernel).as<uint32_t>();
  in.cell_start = own(cell_start.impl(), kernel).as<uint32_t>();
  in.cell_end = own(cell_end.impl(), kernel).as<uint32_t>();
  in.cell_count = grid_cell_count(p.grid);
  in.n = p.n;
  in.first = p.first;
  in.end = sph_range_end(p);
  in.dims[0] = p.grid.dims.x;
  in.dims[1] = p.grid.dims.y;
  in.dims[2] = p.grid.dims.z;
  in.h2 = h2;
  in.max_candidates = p.max_candidates;
  in.fp32 = sph_in_fp32();
  return in;
}

// Finds every particle's neighbours into sph_lists_ (sph::walk_rows, then the candidate test row
// by row) and calls found(chunk, i, count, r2) with each particle's squared distances, in list
// order. With `reach`, the test first lists the candidates within its radius, records them and
// keeps those within h; or tests only the recorded ones of each row that fits a mask. Either way
// the lists are those of the plain test (the same r2 bits, the same order).
template <class T, class Found>
void CpuBackend::build_sph_lists(const SphListInputs& in, size_t chunks, Found&& found,
                                 const SphListReach& reach) {
  constexpr bool fp32 = std::is_same_v<T, float>;
  sph_lists_.reset(in.n, chunks);
  const Soa<T>& xyz = soa_positions<T>(pool_, in.positions, in.n);
  const bool record = reach.mode == SphReach::record && reach.rows;
  const bool walk = reach.mode == SphReach::walk && reach.rows;
  const T h2 = T(in.h2), test_h2 = T(record ? reach.reach2 : in.h2);
  pool_.run_chunks(in.end - in.first, chunks, [&](size_t chunk, size_t b, size_t e) {
    b += in.first;
    e += in.first;
    // Per-thread scratch, kept between calls (60,016 entries at the default candidate cap).
    static thread_local std::vector<uint32_t> index;
    static thread_local std::vector<T> r2;
    // The row tests' slack: whole vectors are stored.
    index.resize(std::max(index.size(), size_t(in.max_candidates) + 16));
    r2.resize(std::max(r2.size(), size_t(in.max_candidates) + 16));
    for (size_t i = b; i < e; ++i) {
      const uint32_t self = uint32_t(i);
      const T px = xyz.x[i], py = xyz.y[i], pz = xyz.z[i];
      const sph::RowMasks<const uint32_t> recorded{walk ? reach.rows + i : nullptr, in.n};
      uint32_t count = 0;
      bool overflow = false;
      const uint32_t candidates = sph::walk_rows(
          in.cells[i], in.dims, in.cell_start, in.cell_end, in.max_candidates, overflow,
          [&](uint32_t row, uint32_t f, uint32_t l) {
            if (l == f) return;
            if (walk && sph::row_fits_mask(f, l)) {
              count += neighbors_masked(&xyz.x[f], &xyz.y[f], &xyz.z[f], f,
                                        sph::load_row_mask(recorded, row), px, py, pz, h2, self,
                                        index.data() + count, r2.data() + count);
            } else if constexpr (fp32) {
              count += sph_simd_->neighbors_row(&xyz.x[f], &xyz.y[f], &xyz.z[f], f, l - f, px,
                                                py, pz, test_h2, self, index.data() + count,
                                                r2.data() + count);
            } else {
              count += neighbors_row(&xyz.x[f], &xyz.y[f], &xyz.z[f], f, l - f, px, py, pz, test_h2,
                                     self, index.data() + count, r2.data() + count);
            }
          });
      if (record) {
        write_row_masks(in, self, index.data(), count, reach.rows);
        count = keep_within(index.data(), r2.data(), count, h2);
      }
      sph_lists_.append(chunk, self, index.data(), count, candidates, overflow);
      found(chunk, self, count, r2.data(), xyz);
    }
  });
  sph_lists_.remember(in);
}

size_t CpuBackend::sph_chunks(uint32_t n) const {
  return chunk_count(pool_, n, 256);
}

void CpuBackend::ensure_sph_lists(const SphListInputs& in) {
  const size_t chunks = sph_chunks(in.end - in.first);
  if (sph_lists_.matches(in, pool_)) return;
  if (in.fp32)
    build_sph_lists<float>(in, chunks, [](size_t, uint32_t, uint32_t, const float*, const auto&) {});
  else
    build_sph_lists<double>(in, chunks,
                            [](size_t, uint32_t, uint32_t, const double*, const auto&) {});
}

void CpuBackend::run_own(const KernelArgs<KernelId::sph_density>& a) {
  auto& [p, items_, positions, cells, cell_start, cell_end, density, pressure, stats, velocities,
         neighbor_state, reach_rows, neighbor_rows] = a;
  const char* k = "sph_density";
  const auto cd = device_params<double>(p);  // the lists' key and the reach radius
  SphListInputs in = sph_list_inputs(p, cells, cell_start, cell_end, cd.h2, k);
  in.positions = own(positions.impl(), k).as<double>();
  double* rho = own(density.impl(), k).as<double>();
  double* pr = own(pressure.impl(), k).as<double>();
  uint32_t* words = own(stats.impl(), k).as<uint32_t>();
  uint32_t* rows = neighbor_rows ? own(neighbor_rows->impl(), k).as<uint32_t>() : nullptr;
  hd::V4<double>* state =
      neighbor_state ? own(neighbor_state->impl(), k).as<hd::V4<double>>() : nullptr;
  const double* vel = state ? own(velocities->impl(), k).as<double>() : nullptr;
  SphListReach reach{p.reach, cd.reach2, nullptr};
  if (reach_rows && p.reach != SphReach::none)
    reach.rows = own(reach_rows->impl(), k).as<uint32_t>();
  const size_t chunks = sph_chunks(sph_range_count(p));
  std::vector<ChunkStats> st(chunks);
  // sph::density_at's sum over the neighbour list: the particle itself (r = 0, term 1) first,
  // then its neighbours; candidates beyond h add exactly nothing there. In T: fp64, or fp32
  // (the SIMD density sum, whose lanes add in their own fixed order).
  auto run = [&]<class T>(const SphStepLayout<T>& c) {
    const SimdPairConstants simd{float(c.h2), float(c.inv_h), float(c.inv_h2), 0.0f, 0.0f,
                                 c.model == SphPressureModel::thesis ? 1u : 0u, 0u};
    build_sph_lists<T>(
        in, chunks,
        [&](size_t chunk, uint32_t i, uint32_t count, const T* r2, const Soa<T>& xyz) {
          ChunkStats& s = st[chunk];
          T sum, images;
          if constexpr (std::is_same_v<T, float>) {
            sum = sph_simd_->density_sum(r2, count, simd);
            images = fp32_wall_images_density(*sph_simd_, c, simd, xyz, i, sph_lists_.list(i),
                                              count);
          } else {
            sum = c.model != SphPressureModel::thesis ? spiky_density_sum(r2, count, c)
                                                      : density_sum(r2, count, c.inv_h2);
            images = wall_images_density(c, in.positions, i, sph_lists_.list(i), count);
          }
          const T rho_i = c.density * (T(1) + sum) + images;
          rho[i] = double(rho_i);
          pr[i] = double(sph::pressure_of(rho_i, c));
          s.max_candidates = std::max(s.max_candidates, sph_lists_.candidates(i));
          s.max_neighbors = std::max(s.max_neighbors, count + 1);
          if (rho[i] > s.max_density) s.max_density = rho[i];  // NaN is reported as non-finite
          if (sph_lists_.overflow(i)) s.overflow = std::min(s.overflow, i);
          if (!std::isfinite(rho[i]) || !std::isfinite(pr[i]))
            s.non_finite = std::min(s.non_finite, i);
          if (rows) write_row_masks(in, i, sph_lists_.list(i), count, rows);
          if (state)
            sph::store_state(state, i,
                             sph::make_neighbor(load3(in.positions, i), load3(vel, i), rho[i],
                                                pr[i]));
        },
        reach);
  };
  if (in.fp32)
    run(device_params<float>(p));
  else
    run(cd);
  merge_sph_stats(words, st);
}

CpuBackend::SphForceBuffers CpuBackend::sph_force_buffers(
    const KernelArgs<KernelId::sph_forces>& a) {
  auto& [p, items_, positions, velocities, density, pressure, cells, cell_start, cell_end, accel,
         stats, neighbor_state, neighbor_rows] = a;
  const char* k = "sph_forces";
  SphListInputs in = sph_list_inputs(p, cells, cell_start, cell_end, device_params<double>(p).h2, k);
  const double* pos = own(positions.impl(), k).as<double>();
  in.positions = pos;
  ensure_sph_lists(in);
  return {pos,
          own(velocities.impl(), k).as<double>(),
          own(density.impl(), k).as<double>(),
          own(pressure.impl(), k).as<double>(),
          own(accel.impl(), k).as<double>(),
          own(stats.impl(), k).as<uint32_t>(),
          neighbor_state ? own(neighbor_state->impl(), k).as<hd::V4<double>>() : nullptr};
}

void CpuBackend::run_own(const KernelArgs<KernelId::sph_forces>& a) {
  // neighbor_rows is not read: the masks are sph_density's neighbour lists plus each particle
  // itself, and the lists below are those lists (or a fresh walk that finds the same ones), so
  // the result is the same with or without them.
  if (sph_in_fp32()) return sph_forces_fp32(a);
  const SphStepParams& p = a.p;
  const auto c = device_params<double>(p);
  const auto [pos, vel, rho, pr, acc_out, words, state] = sph_force_buffers(a);
  const size_t chunks = sph_chunks(sph_range_count(p));
  std::vector<ChunkStats> st(chunks);
  // p / rho^2 once per particle rather than once per pair (the same bits: the shared function),
  // here or in sph_density's neighbour state.
  std::vector<double>& p_rho2 = sph_p_rho2_;
  if (!state) {
    p_rho2.resize(p.n);
    pool_.parallel_for(p.n, 8192, [&](size_t b, size_t e) {
      for (size_t i = b; i < e; ++i) p_rho2[i] = sph::pressure_over_rho2(pr[i], rho[i]);
    });
  }
  auto fetch = [&](uint32_t j) {
    return state ? sph::load_state(state, j)
                 : sph::Neighbor<double>{load3(pos, j), load3(vel, j), rho[j], p_rho2[j]};
  };
  // sph::force_at's pair terms over the neighbour list (the same neighbours in the same order),
  // for the particles of the range.
  pool_.run_chunks(sph_range_count(p), chunks, [&](size_t chunk, size_t b, size_t e) {
    b += p.first;
    e += p.first;
    ChunkStats& s = st[chunk];
    for (size_t i = b; i < e; ++i) {
      const uint32_t self = uint32_t(i);
      const auto me = fetch(self);
      const uint32_t* list = sph_lists_.list(self);
      const uint32_t count = sph_lists_.count(self);
      V acc{0, 0, 0};
      for (uint32_t n = 0; n < count; ++n) {
        const uint32_t j = list[n];
        const sph::Neighbor<double> o = fetch(j);
        const V d = me.x - o.x;
        acc = acc + sph::pair_accel(me, o, d, sph::dot(d, d), c);
      }
      // The wall images of the particle itself and of its neighbours (sph::WallMirrors).
      const auto mirrors = c.walls ? sph::wall_mirrors(me.x, c) : sph::WallMirrors<double>{};
      if (mirrors.axes) {
        acc = acc + sph::wall_image_accel(me, me, mirrors, c);
        for (uint32_t n = 0; n < count; ++n)
          acc = acc + sph::wall_image_accel(me, fetch(list[n]), mirrors, c);
      }
      const double inv_mass = pos[4 * i + 3];
      const V a = sph::total_accel(acc, inv_mass, c);
      store3(acc_out, i, a, double(count));
      add_force_stats(s, sph_lists_, self, finite3(a), inv_mass > 0, sph::dot(a, a));
    }
  });
  merge_sph_stats(words, st);
}

void CpuBackend::run_own(const KernelArgs<KernelId::sph_integrate>& a) {
  auto& [p, items_, x0, v0, vk, accel, x_out, v_out, sum_x, sum_v, stats] = a;
  using V4 = hd::V4<double>;
  auto in = [](const Buffer<Real4>* b) {
    return b ? static_cast<const CpuBuffer&>(b->impl()).as<V4>() : nullptr;
  };
  auto out = [](Buffer<Real4>* b) {
    return b ? static_cast<CpuBuffer&>(b->impl()).as<V4>() : nullptr;
  };
  const auto layout = device_params<double>(p);
  const size_t chunks = chunk_count(pool_, sph_range_count(p), 2048);
  std::vector<ChunkStats> st(chunks);
  pool_.run_chunks(sph_range_count(p), chunks, [&](size_t chunk, size_t b, size_t e) {
    b += p.first;
    e += p.first;
    ChunkStats& s = st[chunk];
    for (size_t i = b; i < e; ++i) {
      const auto r =
          sph::integrate_particle(uint32_t(i), layout, in(x0), in(&v0), in(vk), in(&accel),
                                  out(x_out), out(&v_out), out(sum_x), out(sum_v));
      if (r.non_finite) {
        s.non_finite = std::min(s.non_finite, uint32_t(i));
        continue;
      }
      s.max_speed2 = std::max(s.max_speed2, r.speed2);
      s.max_disp2 = std::max(s.max_disp2, r.disp2);
      s.outside += r.outside ? 1u : 0u;
    }
  });
  merge_sph_stats(static_cast<CpuBuffer&>(stats.impl()).as<uint32_t>(), st);
}

}  // namespace masav::cpu
