#pragma once
// Nebula lighting (thesis Eq. 2.4-2.6, [Magnor 2005]), shared by the CPU reference (T = double)
// and CUDA (T = float); shaders/common/nebula.glsl is the GLSL twin.
//
// The optical depth of a segment a -> b is the path integral of the density grid (piecewise
// constant per cell, from cloud_density) times kappa / albedo. Two discretisations:
//   exact     voxel traversal (Amanatides & Woo): the segment is cut at every cell face it
//             crosses and each piece weighs its cell's density by its exact length. No step
//             error at all for the grid; at most dims.x + dims.y + dims.z + 3 pieces.
//   midpoint  n = ceil(length / step) equal steps, the density at each step's midpoint. The grid
//             is discontinuous at cell faces, so each crossed face costs up to one step times the
//             density jump: the error falls as O(step) (tests: test_nebula.cpp measure it halving
//             with the step).
// Against the smooth |psi|^2 itself, the grid's own error falls with the cell size l.
#include <cstdint>

#include "engine/kernels/atom_params.h"
#include "engine/kernels/grid_cell.h"
#include "engine/kernels/hd_vec.h"
#include "engine/kernels/volume_sample.h"

namespace masav::nebula {

constexpr double kPi = 3.14159265358979323846;

template <class T>
struct Grid {
  hd::V3<T> origin;
  T cell;
  uint32_t dims[3];
};

template <class T>
MASAV_HD inline Grid<T> grid_of(const GridParams& g) {
  return Grid<T>{{T(g.origin.x), T(g.origin.y), T(g.origin.z)},
                 T(g.cell_size),
                 {g.dims.x, g.dims.y, g.dims.z}};
}

// Integral of the density along a -> b (the part inside the grid). density(id) reads cell id.
template <class T, class Density>
MASAV_HD inline T path_integral(const Grid<T>& g, hd::V3<T> a, hd::V3<T> b, OpticalPath mode,
                                T step, Density&& density) {
  const hd::V3<T> d = b - a;
  const T len = hd::length(d);
  if (!(len > T(0))) return T(0);
  const hd::V3<T> dir = d * (T(1) / len);
  const hd::V3<T> hi{g.origin.x + T(g.dims[0]) * g.cell, g.origin.y + T(g.dims[1]) * g.cell,
                     g.origin.z + T(g.dims[2]) * g.cell};
  T t0 = T(0), t1 = len;
  if (!volume::slab(a, dir, g.origin, hi, t0, t1)) return T(0);
  auto cell_of = [&](hd::V3<T> p, int ax) {
    const T f = hd::floor_t((hd::comp(p, ax) - hd::comp(g.origin, ax)) / g.cell);
    return f <= T(0) ? 0 : (f >= T(g.dims[ax] - 1u) ? int(g.dims[ax] - 1u) : int(f));
  };
  auto id_of = [&](const int c[3]) {
    return grid::cell_id(uint32_t(c[0]), uint32_t(c[1]), uint32_t(c[2]), g.dims[1], g.dims[2]);
  };
  T sum = T(0);
  if (mode == OpticalPath::midpoint) {
    uint32_t n = uint32_t(hd::ceil_t((t1 - t0) / step));
    n = n < 1u ? 1u : (n > kMaxPathSteps ? kMaxPathSteps : n);
    const T h = (t1 - t0) / T(n);
    for (uint32_t i = 0; i < n; ++i) {
      const hd::V3<T> p = a + dir * (t0 + (T(i) + T(0.5)) * h);
      const int c[3] = {cell_of(p, 0), cell_of(p, 1), cell_of(p, 2)};
      sum += density(id_of(c)) * h;
    }
    return sum;
  }
  // Voxel traversal from the entry point.
  const hd::V3<T> p0 = a + dir * t0;
  int c[3] = {cell_of(p0, 0), cell_of(p0, 1), cell_of(p0, 2)};
  int stepc[3];
  T tnext[3], tdelta[3];
  for (int ax = 0; ax < 3; ++ax) {
    const T da = hd::comp(dir, ax);
    stepc[ax] = da > T(0) ? 1 : (da < T(0) ? -1 : 0);
    if (stepc[ax] == 0) {
      tnext[ax] = T(volume::kFar);
      tdelta[ax] = T(volume::kFar);
    } else {
      const T face = hd::comp(g.origin, ax) + T(c[ax] + (stepc[ax] > 0 ? 1 : 0)) * g.cell;
      tnext[ax] = (face - hd::comp(a, ax)) / da;
      tdelta[ax] = g.cell / hd::abs_t(da);
    }
  }
  T t = t0;
  const uint32_t max_pieces = g.dims[0] + g.dims[1] + g.dims[2] + 3u;
  for (uint32_t it = 0; it < max_pieces; ++it) {
    const int ax =
        tnext[0] < tnext[1] ? (tnext[0] < tnext[2] ? 0 : 2) : (tnext[1] < tnext[2] ? 1 : 2);
    const T tn = hd::min_t(tnext[ax], t1);
    if (tn > t) sum += density(id_of(c)) * (tn - t);
    if (tnext[ax] >= t1) break;
    t = tn;
    c[ax] += stepc[ax];
    if (c[ax] < 0 || c[ax] >= int(g.dims[ax])) break;
    tnext[ax] += tdelta[ax];
  }
  return sum;
}

// Scattered fraction per steradian P(tau, cos theta) from a phase table (rows x bins, the
// scattered part of each scatter_table bin: make_phase_table() takes the unscattered photons,
// which the thesis's table keeps in the forward bin, out in double precision -- they are the
// star seen through the cell, not dust light). Bilinear in tau (rows tau_step apart, clamped)
// and in cos theta (between bin centres, clamped).
template <class T, class Table>
MASAV_HD inline T phase(const NebulaLightParams& p, T tau, T mu, Table&& table) {
  const uint32_t rows = p.table_rows, bins = p.table_bins;
  const T fr = hd::clamp_t(tau / T(p.table_tau_step), T(0), T(rows - 1u));
  const uint32_t r0 = uint32_t(fr), r1 = r0 + 1u < rows ? r0 + 1u : r0;
  const T wr = fr - T(r0);
  const T fb = hd::clamp_t((mu + T(1)) * T(bins) * T(0.5) - T(0.5), T(0), T(bins - 1u));
  const uint32_t b0 = uint32_t(fb), b1 = b0 + 1u < bins ? b0 + 1u : b0;
  const T wb = fb - T(b0);
  const T v0 = table(r0 * bins + b0) * (T(1) - wb) + table(r0 * bins + b1) * wb;
  const T v1 = table(r1 * bins + b0) * (T(1) - wb) + table(r1 * bins + b1) * wb;
  const T per_bin = v0 * (T(1) - wr) + v1 * wr;
  return per_bin / (T(2) * T(kPi) * (T(2) / T(bins)));
}

// Eq. 2.4: L_ill = Phi / (4 pi r^2) exp(-tau_opt(nucleus -> x)), r clamped to the core radius.
template <class T, class Density>
MASAV_HD inline T illumination(const NebulaLightParams& p, hd::V3<T> x, Density&& density) {
  const Grid<T> g = grid_of<T>(p.grid);
  const hd::V3<T> c{T(p.nucleus.x), T(p.nucleus.y), T(p.nucleus.z)};
  const T r = hd::max_t(hd::length(x - c), T(p.core_radius_a0));
  const T tau = path_integral(g, c, x, p.path, T(p.step_a0), density) * T(p.kappa_a2) / T(p.albedo);
  return T(p.source_power_lm) / (T(4) * T(kPi) * r * r) * hd::exp_t(-tau);
}

// Eq. 2.5-2.6: L = L_ill * P(tau_sct of x's cell, cos(light, view)) * exp(-tau_opt(x -> viewer)).
template <class T, class Density, class Table>
MASAV_HD inline T view_light(const NebulaLightParams& p, hd::V3<T> x, T illum, Density&& density,
                             Table&& table) {
  const Grid<T> g = grid_of<T>(p.grid);
  const hd::V3<T> c{T(p.nucleus.x), T(p.nucleus.y), T(p.nucleus.z)};
  const hd::V3<T> v{T(p.viewer.x), T(p.viewer.y), T(p.viewer.z)};
  // The particle's cell, by the hash grid's fp32 rule (so every backend reads the same cell).
  const float origin[3] = {p.grid.origin.x, p.grid.origin.y, p.grid.origin.z};
  const uint32_t dims[3] = {p.grid.dims.x, p.grid.dims.y, p.grid.dims.z};
  const grid::CellCoord cc =
      grid::point_cell(float(x.x), float(x.y), float(x.z), origin, p.grid.inv_cell, dims);
  const T tau_sct =
      T(p.kappa_a2) * density(grid::cell_id(cc.x, cc.y, cc.z, dims[1], dims[2])) * g.cell;
  const hd::V3<T> to_x = x - c, to_v = v - x;
  const T lx = hd::length(to_x), lv = hd::length(to_v);
  const T mu = lx > T(0) && lv > T(0) ? hd::dot(to_x, to_v) / (lx * lv) : T(1);
  const T tau_view =
      path_integral(g, x, v, p.path, T(p.step_a0), density) * T(p.kappa_a2) / T(p.albedo);
  return illum * phase(p, tau_sct, mu, table) * hd::exp_t(-tau_view);
}

}  // namespace masav::nebula
