#include "engine/mesh/mesh_sdf.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <thread>

#include "engine/core/error.h"
#include "engine/mesh/mesh_distance.h"

namespace masav::mesh {
namespace {

// The cell of coordinate x along an axis of n nodes (clamped into the grid) and the position in
// it, t in [0, 1].
void locate(double x, double origin, double spacing, uint32_t n, uint32_t& i, double& t) {
  const double f = std::clamp((x - origin) / spacing, 0.0, double(n - 1));
  i = std::min(uint32_t(f), n - 2);
  t = f - i;
}

struct Cell {
  uint32_t i, j, k;
  double tx, ty, tz;
  double c[2][2][2];  // c[dz][dy][dx]
};

Cell cell_at(const SignedDistanceField& f, Point p) {
  Cell c{};
  locate(p.x, f.origin.x, f.spacing, f.dims.x, c.i, c.tx);
  locate(p.y, f.origin.y, f.spacing, f.dims.y, c.j, c.ty);
  locate(p.z, f.origin.z, f.spacing, f.dims.z, c.k, c.tz);
  for (int dz = 0; dz < 2; ++dz)
    for (int dy = 0; dy < 2; ++dy)
      for (int dx = 0; dx < 2; ++dx) c.c[dz][dy][dx] = f.node(c.i + dx, c.j + dy, c.k + dz);
  return c;
}

double lerp(double a, double b, double t) {
  return a + t * (b - a);
}

}  // namespace

SdfGrid sdf_grid(const Bounds& b, const SdfParams& p) {
  if (!(std::isfinite(p.spacing) && p.spacing > 0))
    throw_invalid("mesh sdf", "spacing", fmt::format("{}", p.spacing), "a finite number > 0");
  if (!(std::isfinite(p.padding) && p.padding >= 0))
    throw_invalid("mesh sdf", "padding", fmt::format("{}", p.padding), "a finite number >= 0");
  SdfGrid g;
  g.origin = {b.lo.x - p.padding, b.lo.y - p.padding, b.lo.z - p.padding};
  const Point extent = (b.hi - b.lo) + Point{2 * p.padding, 2 * p.padding, 2 * p.padding};
  // Nodes per axis in double first: an extent of 1e300 at a spacing of 1e-300 does not wrap.
  // The factor below 1 keeps 1.4 / 0.1 at 14 cells, not 15, where the quotient rounds up.
  double n[3];
  const double e[3] = {extent.x, extent.y, extent.z};
  for (int a = 0; a < 3; ++a) n[a] = std::max(std::ceil(e[a] / p.spacing * (1 - 1e-12)), 1.0) + 1;
  const double total = n[0] * n[1] * n[2];
  if (!(total <= double(kMaxSdfNodes)))
    throw_invalid(
        "mesh sdf", "grid",
        fmt::format("{:.0f} x {:.0f} x {:.0f} nodes at spacing {}", n[0], n[1], n[2], p.spacing),
        fmt::format("at most {} nodes: a spacing of about {:.3g} or more fits this mesh "
                    "and padding",
                    kMaxSdfNodes, p.spacing * std::cbrt(total / double(kMaxSdfNodes)) * 1.05));
  g.dims = {uint32_t(n[0]), uint32_t(n[1]), uint32_t(n[2])};
  return g;
}

double SignedDistanceField::sample(Point p) const {
  const Cell c = cell_at(*this, p);
  double z[2];
  for (int dz = 0; dz < 2; ++dz)
    z[dz] = lerp(lerp(c.c[dz][0][0], c.c[dz][0][1], c.tx), lerp(c.c[dz][1][0], c.c[dz][1][1], c.tx),
                 c.ty);
  return lerp(z[0], z[1], c.tz);
}

Point SignedDistanceField::gradient(Point p) const {
  const Cell c = cell_at(*this, p);
  const double wx[2] = {1 - c.tx, c.tx}, wy[2] = {1 - c.ty, c.ty}, wz[2] = {1 - c.tz, c.tz};
  Point g{};
  for (int a = 0; a < 2; ++a)
    for (int b = 0; b < 2; ++b) {
      g.x += (c.c[a][b][1] - c.c[a][b][0]) * wy[b] * wz[a];
      g.y += (c.c[a][1][b] - c.c[a][0][b]) * wx[b] * wz[a];
      g.z += (c.c[1][a][b] - c.c[0][a][b]) * wx[b] * wy[a];
    }
  return (1 / spacing) * g;
}

double SignedDistanceField::min_value() const {
  return values.empty() ? 0 : *std::min_element(values.begin(), values.end());
}
double SignedDistanceField::max_value() const {
  return values.empty() ? 0 : *std::max_element(values.begin(), values.end());
}

SignedDistanceField build_sdf(const TriangleMesh& m, const SdfParams& p, std::string_view where) {
  const SdfGrid g = sdf_grid(m.bounds(), p);
  const MeshDistance dist(m, where);
  SignedDistanceField f;
  f.origin = g.origin;
  f.spacing = p.spacing;
  f.dims = g.dims;
  f.values.resize(g.nodes());
  // z-slices dealt round the threads; a row starts its search from the triangle nearest its
  // previous node (a hint changes the time, never the value).
  auto slices = [&](uint32_t first, uint32_t step) {
    for (uint32_t k = first; k < f.dims.z; k += step) {
      uint32_t hint = MeshDistance::kNoHint;
      for (uint32_t j = 0; j < f.dims.y; ++j)
        for (uint32_t i = 0; i < f.dims.x; ++i)
          f.values[f.index(i, j, k)] = dist.signed_distance(f.node_position(i, j, k), &hint);
    }
  };
  uint32_t threads = p.threads ? p.threads : std::max(1u, std::thread::hardware_concurrency());
  threads = std::min({threads, f.dims.z, 256u});
  if (threads <= 1) {
    slices(0, 1);
  } else {
    std::vector<std::jthread> pool;
    for (uint32_t t = 0; t < threads; ++t) pool.emplace_back(slices, t, threads);
  }
  return f;
}

}  // namespace masav::mesh
