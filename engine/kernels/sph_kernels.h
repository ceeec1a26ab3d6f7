#pragma once
// SPH math shared by the CPU reference (T = double) and CUDA (T = float): smoothing kernels,
// the Tait equation of state, the pair terms of both pressure models, box walls as mirror
// images, and the per-particle neighbour walks (the integrator's stages:
// engine/kernels/sph_integrate_body.h). shaders/common/sph.glsl is the GLSL twin.
//
// Smoothing kernels (support radius h, q = r/h), Mueller et al. 2003 / thesis Eq. 4.7:
//   poly6        W(r)      = 315/(64 pi h^3) (1 - q^2)^3            (thesis density, Eq. 4.4)
//   spiky        W(r)      = 15/(pi h^3) (1 - q)^3                   (wcsph and dfsph density)
//   spiky grad   grad W(r) = -45/(pi h^4) (1 - q)^2 r_hat            (wcsph pressure)
//   thesis grad  grad W(r) = -45/(pi h^3) (1 - q)^3 r_hat            (Eq. 4.7 as printed)
//   viscosity    lap W(r)  =  45/(pi h^5) (1 - q)                    (Eq. 4.5)
// r_hat points from the neighbour j to the particle i. Every coefficient that holds a mass,
// a viscosity or a pressure constant is computed once on the host in double (SphStepLayout,
// device_params in engine/kernels/sph_kernel_params.h).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <type_traits>
#if !defined(__CUDA_ARCH__)
#include <bit>
#endif

#include "engine/core/hd.h"
#include "engine/kernels/sph_kernel_params.h"

namespace masav::sph {

template <class T>
struct V3 {
  T x, y, z;
};
template <class T>
MASAV_HD inline V3<T> operator+(V3<T> a, V3<T> b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
template <class T>
MASAV_HD inline V3<T> operator-(V3<T> a, V3<T> b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
template <class T>
MASAV_HD inline V3<T> operator*(T s, V3<T> a) {
  return {s * a.x, s * a.y, s * a.z};
}
template <class T>
MASAV_HD inline T dot(V3<T> a, V3<T> b) {
  return (a.x * b.x + a.y * b.y) + a.z * b.z;
}

// Pressure from density. wcsph: Tait, p = B ((rho/rho0)^7 - 1), clamped at 0 when asked (free
// surfaces). thesis: the force needs no pressure; p = c^2 (rho - rho0) is reported for output.
// dfsph: none here (its pressure comes from the solves, engine/kernels/dfsph_kernels.h).
template <class T>
MASAV_HD inline T pressure_of(T rho, const SphStepLayout<T>& c) {
  if (c.model == SphPressureModel::dfsph) return T(0);  // the solves' pressure, not a state's
  if (c.model == SphPressureModel::thesis) return c.eos * (rho - c.rest_density);
  const T x = rho * c.inv_rest_density;
  const T x2 = x * x;
  T p = c.eos * (x2 * x2 * x2 * x - T(1));
  if (c.clamp_negative_pressure && p < T(0)) p = T(0);
  return p;
}

// Box walls as mirror images (wcsph): the fluid near a wall continues beyond it as its own
// reflection. Particle i sees, besides its neighbours j, the images of every j (itself
// included) across each wall within h of it, and across their combinations at edges and
// corners: up to 7 images, one reflection per axis (the nearer wall of an axis; a box at least
// 2h wide never has both within h). An image carries its particle's density and p / rho^2 and
// the opposite velocity (no-slip: the wall is at rest halfway between). The image terms are the
// pair terms themselves, so particle i and j's image contribute exactly what j and i's image
// would: the walls add density and pressure forces that derive from the same internal energy
// as the fluid's (no energy enters through a wall), hold a lattice at rest against a wall and in
// a corner as the interior holds it, and the no-slip viscosity only dissipates
// (sum over a pair: -|v_i + v_j|^2). A lattice dx/2 from a wall continues into its images with
// the same spacing, so its first layer has the interior's density.
template <class T>
struct WallMirrors {
  T plane[3];     // axis a reflects x_a to 2 plane[a] - x_a
  uint32_t axes;  // bit a set: a wall within h on axis a
};

// The mirrors of a particle at x in the box [lo, hi] with support h (h2 = h^2).
template <class T>
MASAV_HD inline WallMirrors<T> box_mirrors(V3<T> x, const T lo[3], const T hi[3], T h2) {
  const T xs[3] = {x.x, x.y, x.z};
  WallMirrors<T> m{{T(0), T(0), T(0)}, 0u};
  for (int a = 0; a < 3; ++a) {
    const T to_lo = xs[a] - lo[a], to_hi = hi[a] - xs[a];
    const bool low = to_lo <= to_hi;
    const T d = low ? to_lo : to_hi;
    m.plane[a] = low ? lo[a] : hi[a];
    if (d * d < h2 || d < T(0)) m.axes |= 1u << a;
  }
  return m;
}
template <class T>
MASAV_HD inline WallMirrors<T> wall_mirrors(V3<T> x, const SphStepLayout<T>& c) {
  return box_mirrors(x, c.lo, c.hi, c.h2);
}

// Calls f(d, r2, s) for each image of x_j within h of x_i, d = x_i - image, s the mirror set
// (bit a: reflected across axis a's wall).
template <class T, class F>
MASAV_HD inline void for_each_wall_image_set(V3<T> xi, V3<T> xj, const WallMirrors<T>& m, T h2,
                                             F&& f) {
  const T direct[3] = {xi.x - xj.x, xi.y - xj.y, xi.z - xj.z};
  // Each distance to the plane first: near a wall both are small and exact in fp32.
  const T mirrored[3] = {(xi.x - m.plane[0]) + (xj.x - m.plane[0]),
                         (xi.y - m.plane[1]) + (xj.y - m.plane[1]),
                         (xi.z - m.plane[2]) + (xj.z - m.plane[2])};
  // One image at a time on CUDA: unrolled, the seven sets' terms cost the force walk registers.
#if defined(__CUDA_ARCH__)
#pragma unroll 1
#endif
  for (uint32_t s = 1; s < 8u; ++s) {
    if (s & ~m.axes) continue;
    const V3<T> d{(s & 1u) ? mirrored[0] : direct[0], (s & 2u) ? mirrored[1] : direct[1],
                  (s & 4u) ? mirrored[2] : direct[2]};
    const T r2 = dot(d, d);
    if (r2 < h2) f(d, r2, s);
  }
}

// Calls f(d, r2) for each image of x_j within h of x_i, d = x_i - image.
template <class T, class F>
MASAV_HD inline void for_each_wall_image(V3<T> xi, V3<T> xj, const WallMirrors<T>& m, T h2, F&& f) {
  for_each_wall_image_set(xi, xj, m, h2, [&](V3<T> d, T r2, uint32_t) { f(d, r2); });
}

// Cell coordinates of a cell id (thesis Eq. 4.2 inverted).
MASAV_HD inline void cell_coords(uint32_t id, const uint32_t dims[3], int out[3]) {
  const uint32_t yz = dims[1] * dims[2];
  out[0] = int(id / yz);
  out[1] = int((id % yz) / dims[2]);
  out[2] = int(id % dims[2]);
}

// The sorted range holding the 3 cells (x, y, z-1 .. z+1) of one row of the 27-cell block:
// consecutive cell ids, so their points are contiguous in cell order, from the first cell's start
// to the last one's end. That needs the counting build's tables, where an empty cell reads
// [k, k) with k the points in lower cells (SphGridView::prefix_ranges); two loads instead of six.
// [0, 0) when all 3 are empty.
MASAV_HD inline void row_range(int x, int y, int z, const uint32_t dims[3],
                               const uint32_t* cell_start, const uint32_t* cell_end,
                               uint32_t& first, uint32_t& last) {
  const int z0 = z > 0 ? z - 1 : 0;
  const int z1 = z + 1 < int(dims[2]) ? z + 1 : int(dims[2]) - 1;
  const uint32_t base = (uint32_t(x) * dims[1] + uint32_t(y)) * dims[2];
  first = cell_start[base + uint32_t(z0)];
  last = cell_end[base + uint32_t(z1)];
  if (last <= first) first = last = 0;
}

// Visits the 9 rows of the 27 cells around `cell` in the order every backend sums in (x
// outermost, then y), each with its index in that order, 3 (dx + 1) + (dy + 1), and its sorted
// range [first, last) along z. A row outside the grid is empty; so is every row from the one
// that would pass max_candidates candidates on, which sets `overflow`. Returns the candidates
// of the rows walked.
template <class Row>
MASAV_HD inline uint32_t walk_rows(uint32_t cell, const uint32_t dims[3],
                                   const uint32_t* cell_start, const uint32_t* cell_end,
                                   uint32_t max_candidates, bool& overflow, Row&& row) {
  int c[3];
  cell_coords(cell, dims, c);
  uint32_t candidates = 0;
  overflow = false;
  for (int dx = -1; dx <= 1; ++dx) {
    for (int dy = -1; dy <= 1; ++dy) {
      const int x = c[0] + dx, y = c[1] + dy;
      uint32_t first = 0, last = 0;
      if (!overflow && x >= 0 && x < int(dims[0]) && y >= 0 && y < int(dims[1])) {
        row_range(x, y, c[2], dims, cell_start, cell_end, first, last);
        if (last - first > max_candidates - candidates) {
          overflow = true;
          first = last = 0;
        }
        candidates += last - first;
      }
      row(uint32_t(3 * (dx + 1) + (dy + 1)), first, last);
    }
  }
  return candidates;
}

// walk_rows' non-empty rows only, as row(first, last); the CPU reference vectorises over a row.
template <class Row>
MASAV_HD inline uint32_t walk_neighbor_rows(uint32_t cell, const uint32_t dims[3],
                                            const uint32_t* cell_start, const uint32_t* cell_end,
                                            uint32_t max_candidates, bool& overflow, Row&& row) {
  return walk_rows(cell, dims, cell_start, cell_end, max_candidates, overflow,
                   [&](uint32_t, uint32_t first, uint32_t last) {
                     if (last > first) row(first, last);
                   });
}

// One particle's neighbour row masks (kSphRowMaskBits, kSphRowMaskWords in
// sph_kernel_params.h): word w at words[w * stride], i.e. &neighbor_rows[i] with stride n.
template <class W>  // uint32_t where sph_density writes them, const uint32_t where read
struct RowMasks {
  W* words = nullptr;  // null: no masks
  uint32_t stride = 0;
};
template <class W>
MASAV_HD inline RowMasks<W> row_masks(W* neighbor_rows, uint32_t i, uint32_t n) {
  return neighbor_rows ? RowMasks<W>{neighbor_rows + i, n} : RowMasks<W>{};
}
MASAV_HD inline bool row_fits_mask(uint32_t first, uint32_t last) {
  return last - first <= kSphRowMaskBits;
}
MASAV_HD inline void store_row_mask(RowMasks<uint32_t> m, uint32_t row, uint64_t bits) {
  m.words[size_t(2 * row) * m.stride] = uint32_t(bits);
  m.words[size_t(2 * row + 1) * m.stride] = uint32_t(bits >> 32);
}
MASAV_HD inline uint64_t load_row_mask(RowMasks<const uint32_t> m, uint32_t row) {
  return uint64_t(m.words[size_t(2 * row) * m.stride]) |
         uint64_t(m.words[size_t(2 * row + 1) * m.stride]) << 32;
}
// The lowest set bit's index, cleared from `bits` (not 0).
MASAV_HD inline uint32_t take_lowest_bit(uint64_t& bits) {
#if defined(__CUDA_ARCH__)
  const uint32_t b = uint32_t(__ffsll((long long)bits) - 1);
#else
  const uint32_t b = uint32_t(std::countr_zero(bits));
#endif
  bits &= bits - 1;
  return b;
}

// a * b. With Unfused on CUDA, the round-to-nearest product that nvcc never contracts into a
// fused multiply-add with a following sum: a kernel that holds two copies of one walk (the
// density with and without wall images, chosen per warp) must round them alike, or a particle's
// density would change with the particles sharing its warp. Elsewhere the plain product.
template <bool Unfused, class T>
MASAV_HD inline T unfused_mul(T a, T b) {
#if defined(__CUDA_ARCH__)
  if constexpr (Unfused && std::is_same_v<T, float>) return __fmul_rn(a, b);
#endif
  return a * b;
}

// The density sum's term for r^2 < h^2, else 0: the spiky kernel's (1 - q)^3 for wcsph and
// dfsph, whose gradient is the one their pressure force and solves use, or poly6's
// (1 - q^2)^3 for the thesis model (Eq. 4.4). A density and a pressure gradient of the same
// kernel make the wcsph force the exact gradient of the fluid's internal energy, so no pair
// does work that the energy does not store (with poly6 densities and spiky gradients an
// inviscid dam break gained 49% in 0.8 s), and dfsph's solves predict exactly the density they
// correct.
// With Unfused, see unfused_mul.
template <class T, bool Unfused = false>
MASAV_HD inline T density_term(T r2, const SphStepLayout<T>& c) {
  T u = c.model != SphPressureModel::thesis ? T(1) - unfused_mul<Unfused>(sqrt(r2), c.inv_h)
                                            : T(1) - unfused_mul<Unfused>(r2, c.inv_h2);
  u = u > T(0) ? u : T(0);
  return unfused_mul<Unfused>(unfused_mul<Unfused>(u, u), u);
}

// |d|^2, with Unfused as unfused_mul.
template <bool Unfused, class T>
MASAV_HD inline T squared_length(V3<T> d) {
  return unfused_mul<Unfused>(d.x, d.x) + unfused_mul<Unfused>(d.y, d.y) +
         unfused_mul<Unfused>(d.z, d.z);
}

// The density term sum of j's wall images (see WallMirrors) at x_i.
template <class T>
MASAV_HD inline T wall_image_density(V3<T> xi, V3<T> xj, const WallMirrors<T>& m,
                                     const SphStepLayout<T>& c) {
  T sum = T(0);
  for_each_wall_image(xi, xj, m, c.h2, [&](V3<T>, T r2) { sum += density_term(r2, c); });
  return sum;
}

// The density the particle's own images add: the density kernel's terms at its images, like
// any neighbour's. Its gradient is then exactly the own image's pair force in force_at (a pair
// term with p_j = p_i, the image moving opposite), so the energy a particle stores against its
// own image is the energy it gets back.
template <class T>
MASAV_HD inline T own_image_density(V3<T> xi, const WallMirrors<T>& m, const SphStepLayout<T>& c) {
  return c.density * wall_image_density(xi, xi, m, c);
}

template <class T>
struct DensityResult {
  T density;
  uint32_t neighbors;   // points within h, itself included
  uint32_t candidates;  // points examined
  bool overflow;
};

// sph_density's reach masks (SphReach in sph_kernel_params.h) of one particle: recorded (rows:
// candidates within reach2) or walked; mode none leaves them alone.
template <class T>
struct Reach {
  SphReach mode = SphReach::none;
  T reach2 = T(0);
  RowMasks<uint32_t> rows;
};
template <class T>
MASAV_HD inline Reach<T> reach_of(const SphStepLayout<T>& c, uint32_t* reach_rows, uint32_t i) {
  if (!reach_rows || c.reach == SphReach::none) return Reach<T>{};
  return Reach<T>{c.reach, c.reach2, row_masks(reach_rows, i, c.n)};
}

// Density of sorted particle i (thesis Eq. 4.4) at xi, `mirrors` its wall_mirrors (none
// without walls): sum over j within h of m W(r_ij), W as in density_term, plus the terms of
// the wall images. Images = false leaves the images out and is for callers that know
// mirrors.axes == 0 (CUDA's per-warp copy for warps far from the walls); Unfused as
// unfused_mul. pos_at(j) returns V3<T> of sorted particle j. With `masks`, also records which
// candidates of each row lie within h (zero for an empty, missing or too long row). With
// `reach`, records which lie within its radius (the same format), or visits only the recorded
// ones of each row that fits a mask: the candidates it skips lie beyond h, whose terms are 0, so
// the sum adds the same terms in the same order as the whole walk.
template <class T, bool Images, bool Unfused, class PosAt>
MASAV_HD inline DensityResult<T> density_walk(uint32_t self, V3<T> xi,
                                              const WallMirrors<T>& mirrors, uint32_t cell,
                                              const uint32_t dims[3], const uint32_t* cell_start,
                                              const uint32_t* cell_end, uint32_t max_candidates,
                                              const SphStepLayout<T>& c, PosAt&& pos_at,
                                              RowMasks<uint32_t> masks = {},
                                              const Reach<T>& reach = {}) {
  T sum = T(0);
  uint32_t neighbors = 0;
  bool overflow = false;
  const uint32_t candidates =
      walk_rows(cell, dims, cell_start, cell_end, max_candidates, overflow,
                [&](uint32_t row, uint32_t first, uint32_t last) {
                  // Both wrap around in a row too long for them, which stores 0.
                  uint64_t bits = 0, reach_bits = 0;
                  auto visit = [&](uint32_t j) {
                    const T r2 = squared_length<Unfused>(xi - pos_at(j));
                    sum += density_term<T, Unfused>(r2, c);
                    const bool within = r2 < c.h2;
                    if constexpr (Images) {
                      if (within && mirrors.axes && j != self)
                        sum += wall_image_density(xi, pos_at(j), mirrors, c);
                    }
                    neighbors += within ? 1u : 0u;
                    const uint32_t b = (j - first) & (kSphRowMaskBits - 1);
                    bits |= uint64_t(within) << b;
                    reach_bits |= uint64_t(r2 < reach.reach2) << b;
                  };
                  const bool fits = row_fits_mask(first, last);
                  if (reach.mode == SphReach::walk && fits) {
                    const RowMasks<const uint32_t> recorded{reach.rows.words, reach.rows.stride};
                    for (uint64_t rb = load_row_mask(recorded, row); rb != 0;)
                      visit(first + take_lowest_bit(rb));
                  } else {
                    for (uint32_t j = first; j < last; ++j) visit(j);
                  }
                  if (masks.words) store_row_mask(masks, row, fits ? bits : 0);
                  if (reach.mode == SphReach::record)
                    store_row_mask(reach.rows, row, fits ? reach_bits : 0);
                });
  const T own = Images && mirrors.axes ? own_image_density(xi, mirrors, c) : T(0);
  return {c.density * sum + own, neighbors, candidates, overflow};
}

// density_walk with its wall images, the mirrors computed here.
template <class T, class PosAt>
MASAV_HD inline DensityResult<T> density_at(uint32_t self, V3<T> xi, uint32_t cell,
                                            const uint32_t dims[3], const uint32_t* cell_start,
                                            const uint32_t* cell_end, uint32_t max_candidates,
                                            const SphStepLayout<T>& c, PosAt&& pos_at,
                                            RowMasks<uint32_t> masks = {},
                                            const Reach<T>& reach = {}) {
  const WallMirrors<T> mirrors = c.walls ? wall_mirrors(xi, c) : WallMirrors<T>{};
  return density_walk<T, true, false>(self, xi, mirrors, cell, dims, cell_start, cell_end,
                                      max_candidates, c, pos_at, masks, reach);
}

// What the force walk reads of a neighbour: position, velocity, density and p / rho^2 (the
// wcsph pressure term's per-particle factor, computed once per particle where a backend can).
template <class T>
struct Neighbor {
  V3<T> x, v;
  T rho, p_rho2;
};

template <class T>
MASAV_HD inline T pressure_over_rho2(T p, T rho) {
  return p / (rho * rho);
}

template <class T>
MASAV_HD inline Neighbor<T> make_neighbor(V3<T> x, V3<T> v, T rho, T p) {
  return Neighbor<T>{x, v, rho, pressure_over_rho2(p, rho)};
}

// The acceleration neighbour o gives particle `me` (per unit SPH mass), for 0 <= r2 < h^2 with
// d = me.x - o.x. Formulas: see force_at.
template <class T>
MASAV_HD inline V3<T> pair_accel(const Neighbor<T>& me, const Neighbor<T>& o, V3<T> d, T r2,
                                 const SphStepLayout<T>& c) {
  const bool thesis = c.model == SphPressureModel::thesis;
  const T r = sqrt(r2);
  const T u = T(1) - r * c.inv_h;  // 1 - q
  V3<T> a{T(0), T(0), T(0)};
  if (r2 > T(0) && c.model != SphPressureModel::dfsph) {  // pressure along r_hat = d / r
    T s;
    if (thesis)
      s = c.pressure * ((o.rho - me.rho) / o.rho) * (u * u * u);
    else
      s = c.pressure * (me.p_rho2 + o.p_rho2) * (u * u);
    a = (s / r) * d;
  }
  const T w = thesis ? c.viscosity * u / o.rho : c.viscosity * u * (T(2) / (me.rho + o.rho));
  return a + w * (o.v - me.v);
}

// The pair terms of o's wall images (see WallMirrors) on `me`.
template <class T>
MASAV_HD inline V3<T> wall_image_accel(const Neighbor<T>& me, const Neighbor<T>& o,
                                       const WallMirrors<T>& m, const SphStepLayout<T>& c) {
  const Neighbor<T> image{o.x, T(-1) * o.v, o.rho, o.p_rho2};
  V3<T> a{T(0), T(0), T(0)};
  for_each_wall_image(me.x, o.x, m, c.h2,
                      [&](V3<T> d, T r2) { a = a + pair_accel(me, image, d, r2, c); });
  return a;
}

// Calls visit(j) for the candidates of the 27 cells around `cell` (walk_rows' order): with
// `masks` (sph_density's, for the same positions and grid), a row that fits a mask visits only
// its recorded neighbours, in ascending order; other rows visit every candidate. The visitor
// repeats the distance test. Returns the candidates of the rows walked.
template <class Visit>
MASAV_HD inline uint32_t walk_candidates(uint32_t cell, const uint32_t dims[3],
                                         const uint32_t* cell_start, const uint32_t* cell_end,
                                         uint32_t max_candidates, RowMasks<const uint32_t> masks,
                                         bool& overflow, Visit&& visit) {
  return walk_rows(cell, dims, cell_start, cell_end, max_candidates, overflow,
                   [&](uint32_t row, uint32_t first, uint32_t last) {
                     if (last == first) return;
                     if (masks.words && row_fits_mask(first, last)) {
                       for (uint64_t bits = load_row_mask(masks, row); bits != 0;)
                         visit(first + take_lowest_bit(bits));
                     } else {
                       for (uint32_t j = first; j < last; ++j) visit(j);
                     }
                   });
}

template <class T>
struct ForceResult {
  V3<T> accel;
  uint32_t neighbors;  // within h, itself excluded
  uint32_t candidates;
  bool overflow;
};

// Acceleration of sorted particle i from its neighbours (per unit SPH mass), before the inverse
// mass scale and gravity (see total_accel).
//   wcsph:  a_i = sum_j m (p_i/rho_i^2 + p_j/rho_j^2) 45/(pi h^4) (1-q)^2 r_hat
//               + nu sum_j m (v_j - v_i) 2/(rho_i + rho_j) lap W
//           Every pair term is antisymmetric in (i, j) -- also in floating point, since
//           x_i - x_j = -(x_j - x_i) exactly -- so total momentum is conserved.
//   thesis: a_i = kp sum_j m (rho_j - rho_i)/(2 rho_j) 45/(pi h^3) (1-q)^3 r_hat   (Eq. 4.6)
//               + nu sum_j m (v_j - v_i)/rho_j lap W                             (Eq. 4.5)
// pos_at(j) returns V3<T> of sorted particle j, fetch(j) its whole Neighbor<T> (read only for
// neighbours within h); `self` is i's sorted index. With `masks` (density_at's, for these
// positions), a row that fits a mask visits only its recorded neighbours, in the same ascending
// order, so the result is the same bits; the distance test is repeated, so that a compiler
// rounding r2 differently in the two kernels can drop a pair but never add one beyond h.
// With ImagesAfter the wall images come after the direct terms, in a second walk over the same
// neighbours: the particle's own images, then each neighbour's in the walk's order, as the CPU
// reference adds them. The direct walk's loop then holds no image terms; on CUDA (sm_90) it
// needs 48 registers and the images' walk 61-64, where one loop holding both (ImagesAfter
// false: each neighbour's images with its pair term) needs 95.
template <class T, bool ImagesAfter = true, class PosAt, class Fetch>
MASAV_HD inline ForceResult<T> force_at(uint32_t self, const Neighbor<T>& me, uint32_t cell,
                                        const uint32_t dims[3], const uint32_t* cell_start,
                                        const uint32_t* cell_end, uint32_t max_candidates,
                                        const SphStepLayout<T>& c, PosAt&& pos_at, Fetch&& fetch,
                                        RowMasks<const uint32_t> masks = {}) {
  V3<T> acc{T(0), T(0), T(0)};
  uint32_t neighbors = 0;
  bool overflow = false;
  uint32_t candidates = 0;
  if constexpr (ImagesAfter) {
    auto direct = [&](uint32_t j) {
      const V3<T> d = me.x - pos_at(j);
      const T r2 = dot(d, d);
      if (!(r2 < c.h2) || j == self) return;
      ++neighbors;
      acc = acc + pair_accel(me, fetch(j), d, r2, c);
    };
    candidates =
        walk_candidates(cell, dims, cell_start, cell_end, max_candidates, masks, overflow, direct);
    const WallMirrors<T> mirrors = c.walls ? wall_mirrors(me.x, c) : WallMirrors<T>{};
    if (mirrors.axes) {
      acc = acc + wall_image_accel(me, me, mirrors, c);
      auto images = [&](uint32_t j) {
        const V3<T> d = me.x - pos_at(j);
        if (!(dot(d, d) < c.h2) || j == self) return;
        acc = acc + wall_image_accel(me, fetch(j), mirrors, c);
      };
      bool again = false;
      walk_candidates(cell, dims, cell_start, cell_end, max_candidates, masks, again, images);
    }
  } else {  // each neighbour's images with its pair term, the particle's own where it is walked
    const WallMirrors<T> mirrors = c.walls ? wall_mirrors(me.x, c) : WallMirrors<T>{};
    auto both = [&](uint32_t j) {
      const V3<T> d = me.x - pos_at(j);
      const T r2 = dot(d, d);
      if (!(r2 < c.h2)) return;
      if (j == self) {
        if (mirrors.axes) acc = acc + wall_image_accel(me, me, mirrors, c);
        return;
      }
      const Neighbor<T> o = fetch(j);
      if (mirrors.axes) acc = acc + wall_image_accel(me, o, mirrors, c);
      ++neighbors;
      acc = acc + pair_accel(me, o, d, r2, c);
    };
    candidates =
        walk_candidates(cell, dims, cell_start, cell_end, max_candidates, masks, overflow, both);
  }
  return {acc, neighbors, candidates, overflow};
}

// Total acceleration: pair forces scaled by the inverse inertial mass (1 fluid, 1/ratio heavy
// obstacle, 0 pinned), plus gravity for everything that can move.
template <class T>
MASAV_HD inline V3<T> total_accel(V3<T> pair, T inv_mass, const SphStepLayout<T>& c) {
  if (!(inv_mass > T(0))) return {T(0), T(0), T(0)};
  return V3<T>{inv_mass * pair.x + c.gravity[0], inv_mass * pair.y + c.gravity[1],
               inv_mass * pair.z + c.gravity[2]};
}

template <class T>
MASAV_HD inline V3<T> xyz(const hd::V4<T>& v) {
  return V3<T>{v.x, v.y, v.z};
}
// The neighbour state of sorted particle i (kSphStateStride in engine/kernels/sph_kernel_params.h):
// (x, rho) then (v, p / rho^2), side by side.
template <class T>
MASAV_HD inline void store_state(hd::V4<T>* state, uint32_t i, const Neighbor<T>& s) {
  state[kSphStateStride * i] = hd::V4<T>{s.x.x, s.x.y, s.x.z, s.rho};
  state[kSphStateStride * i + 1] = hd::V4<T>{s.v.x, s.v.y, s.v.z, s.p_rho2};
}
template <class T>
MASAV_HD inline V3<T> state_position(const hd::V4<T>* state, uint32_t j) {
  return xyz(state[kSphStateStride * j]);
}
template <class T>
MASAV_HD inline Neighbor<T> load_state(const hd::V4<T>* state, uint32_t j) {
  const hd::V4<T> a = state[kSphStateStride * j], b = state[kSphStateStride * j + 1];
  return Neighbor<T>{V3<T>{a.x, a.y, a.z}, V3<T>{b.x, b.y, b.z}, a.w, b.w};
}

template <class T>
MASAV_HD inline bool finite3(V3<T> v) {
  return isfinite(v.x) && isfinite(v.y) && isfinite(v.z);
}

}  // namespace masav::sph
