#include "engine/mesh/mesh_check.h"

#include <fmt/format.h>

#include <algorithm>
#include <limits>

#include "engine/core/error.h"

namespace masav::mesh {
namespace {

constexpr uint32_t kNone = std::numeric_limits<uint32_t>::max();

// One use of an edge: its vertex pair (smaller index in the high word) and the triangle edge.
struct EdgeUse {
  uint64_t key;
  uint32_t code;  // 3 t + e
  bool operator<(const EdgeUse& o) const { return key != o.key ? key < o.key : code < o.code; }
};

// A triangle's area is zero when its cross product vanishes against its longest edge (relative,
// so that the test does not depend on the mesh's units).
bool is_degenerate(double twice_area, Point a, Point b, Point c) {
  const double e2 = std::max({dot(b - a, b - a), dot(c - b, c - b), dot(a - c, a - c)});
  return !(twice_area > 1e-14 * e2);
}

std::string point(Point p) {
  return fmt::format("({:.9g}, {:.9g}, {:.9g})", p.x, p.y, p.z);
}

struct Analysis {
  MeshCheck check;
  std::vector<uint32_t> opposite;  // per triangle edge, when asked for
};

uint32_t corner(const TriangleMesh& m, uint32_t code, int k) {
  return m.triangles[code / 3][(code % 3 + k) % 3];
}

std::string edge_text(const TriangleMesh& m, uint32_t code) {
  const uint32_t a = corner(m, code, 0), b = corner(m, code, 1);
  return fmt::format("vertices {} {} and {} {}", a, point(m.vertices[a]), b, point(m.vertices[b]));
}

Analysis analyse(const TriangleMesh& m, bool want_neighbours) {
  Analysis r;
  MeshCheck& c = r.check;
  c.triangles = m.triangles.size();
  c.vertices = m.vertices.size();
  c.bounds = m.bounds();
  if (m.triangles.empty()) {
    c.problem = "the mesh has no triangles";
    c.remedy = "give a mesh with at least one triangle";
    return r;
  }
  if (m.triangles.size() > kMaxTriangles) {
    c.problem =
        fmt::format("{} triangles, more than the {} allowed", m.triangles.size(), kMaxTriangles);
    c.remedy = "simplify the mesh";
    return r;
  }
  for (size_t t = 0; t < m.triangles.size(); ++t)
    for (uint32_t v : m.triangles[t])
      if (v >= m.vertices.size()) {
        c.problem = fmt::format("triangle {} names vertex {}, but the mesh has {} vertices", t, v,
                                m.vertices.size());
        c.remedy = "every vertex index must be below the vertex count";
        return r;
      }

  // Areas and the volume; positions relative to the box centre keep the volume's terms small.
  const Point centre = 0.5 * (c.bounds.lo + c.bounds.hi);
  uint64_t first_degenerate = kNone;
  for (size_t t = 0; t < m.triangles.size(); ++t) {
    const auto& tri = m.triangles[t];
    const Point a = m.vertices[tri[0]], b = m.vertices[tri[1]], d = m.vertices[tri[2]];
    const double twice_area = length(cross(b - a, d - a));
    c.area += 0.5 * twice_area;
    c.volume += dot(a - centre, cross(b - centre, d - centre)) / 6.0;
    if (is_degenerate(twice_area, a, b, d)) {
      if (c.degenerate++ == 0) first_degenerate = t;
    }
  }

  std::vector<EdgeUse> uses(3 * m.triangles.size());
  for (uint32_t t = 0; t < m.triangles.size(); ++t)
    for (uint32_t e = 0; e < 3; ++e) {
      const uint32_t a = m.triangles[t][e], b = m.triangles[t][(e + 1) % 3];
      uses[3 * t + e] = {uint64_t(std::min(a, b)) << 32 | std::max(a, b), 3 * t + e};
    }
  std::sort(uses.begin(), uses.end());
  if (want_neighbours) r.opposite.assign(uses.size(), kNone);
  uint32_t first_open = kNone, first_nonmanifold = kNone, first_misoriented = kNone;
  size_t nonmanifold_size = 0, nonmanifold_at = 0;
  for (size_t i = 0; i < uses.size();) {
    size_t j = i + 1;
    while (j < uses.size() && uses[j].key == uses[i].key) ++j;
    const uint32_t code = uses[i].code;  // the group's lowest triangle edge
    if (j - i == 1) {
      if (c.open_edges++ == 0 || code < first_open) first_open = code;
    } else if (j - i > 2) {
      if (c.nonmanifold_edges++ == 0 || code < first_nonmanifold) {
        first_nonmanifold = code;
        nonmanifold_size = j - i;
        nonmanifold_at = i;
      }
    } else {
      const uint32_t other = uses[i + 1].code;
      if (corner(m, code, 0) == corner(m, other, 0)) {
        if (c.misoriented_edges++ == 0 || code < first_misoriented) first_misoriented = code;
      } else if (want_neighbours) {
        r.opposite[code] = other;
        r.opposite[other] = code;
      }
    }
    i = j;
  }

  if (c.degenerate) {
    const auto& tri = m.triangles[first_degenerate];
    c.problem = fmt::format(
        "{} zero-area triangle{}; the first: triangle {} (vertices {} {}, {} {}, {} {})",
        c.degenerate, c.degenerate == 1 ? "" : "s", first_degenerate, tri[0],
        point(m.vertices[tri[0]]), tri[1], point(m.vertices[tri[1]]), tri[2],
        point(m.vertices[tri[2]]));
    c.remedy = "remove the degenerate triangles (merge their vertices) before exporting the mesh";
  } else if (c.nonmanifold_edges) {
    std::string tris;
    for (size_t k = 0; k < nonmanifold_size; ++k)
      tris += fmt::format("{}{}", k ? ", " : "", uses[nonmanifold_at + k].code / 3);
    c.problem = fmt::format(
        "not manifold: {} edge{} shared by three or more triangles; the first: {}, shared by "
        "triangles {}",
        c.nonmanifold_edges, c.nonmanifold_edges == 1 ? "" : "s", edge_text(m, first_nonmanifold),
        tris);
    c.remedy =
        "each edge must belong to exactly two triangles: separate the parts that touch "
        "along it, or remove the extra faces";
  } else if (c.open_edges) {
    c.problem = fmt::format(
        "not watertight: {} open edge{} (used by one triangle only); the first: {}, an edge of "
        "triangle {} alone",
        c.open_edges, c.open_edges == 1 ? "" : "s", edge_text(m, first_open), first_open / 3);
    c.remedy =
        "close the surface (fill the holes in the modelling tool, or check that the "
        "export kept every face)";
  } else if (c.misoriented_edges) {
    uint32_t other = kNone;
    // The other use of the first misoriented edge: found again by its key.
    const uint32_t a = corner(m, first_misoriented, 0), b = corner(m, first_misoriented, 1);
    const uint64_t key = uint64_t(std::min(a, b)) << 32 | std::max(a, b);
    auto it = std::lower_bound(uses.begin(), uses.end(), EdgeUse{key, 0});
    if (it != uses.end() && it + 1 != uses.end()) other = (it + 1)->code;
    c.problem = fmt::format(
        "faces oriented inconsistently: {} edge{} run in the same direction by both of their "
        "triangles; the first: {}, run from the first to the second by triangles {} and {}",
        c.misoriented_edges, c.misoriented_edges == 1 ? "" : "s", edge_text(m, first_misoriented),
        first_misoriented / 3, other / 3);
    c.remedy = fmt::format(
        "orient every face the same way (flip triangle {}, or let the modelling tool make the "
        "normals consistent)",
        other / 3);
  } else if (c.volume < 0) {
    c.problem = fmt::format(
        "the enclosed volume is {:.9g} (negative): the faces' normals point inward", c.volume);
    c.remedy =
        "flip the faces (reverse the vertex order of every triangle) so that their "
        "normals point out of the solid";
  } else if (!(c.volume > 0)) {
    c.problem = "the surface encloses no volume";
    c.remedy = "give a mesh of a solid, not of a flat or inside-out pair of sheets";
  }
  return r;
}

}  // namespace

MeshCheck check_mesh(const TriangleMesh& m) {
  return analyse(m, false).check;
}

std::vector<uint32_t> edge_neighbours(const TriangleMesh& m, std::string_view where) {
  Analysis r = analyse(m, true);
  if (!r.check.closed()) throw Error("", std::string(where), r.check.problem, r.check.remedy);
  return std::move(r.opposite);
}

}  // namespace masav::mesh
