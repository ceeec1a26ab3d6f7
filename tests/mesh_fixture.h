#pragma once
// Meshes made in code for the mesh tests (tests/test_mesh*.cpp): boxes (optionally with every
// face cut into n x n quads), icospheres, and their OBJ, binary STL and ASCII STL files.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <map>
#include <string>
#include <utility>

#include "engine/mesh/triangle_mesh.h"

namespace masav::test {

using mesh::Point;
using mesh::TriangleMesh;

// Appends triangle (a, b, c) turned so that its normal points along `out`.
inline void add_oriented(TriangleMesh& m, uint32_t a, uint32_t b, uint32_t c, Point out) {
  const Point n = mesh::cross(m.vertices[b] - m.vertices[a], m.vertices[c] - m.vertices[a]);
  if (mesh::dot(n, out) >= 0)
    m.triangles.push_back({a, b, c});
  else
    m.triangles.push_back({a, c, b});
}

// The box [lo, hi], every face cut into n x n squares of two triangles, normals outward; vertices
// shared along the box's edges.
inline TriangleMesh box_mesh(Point lo, Point hi, uint32_t n = 1) {
  TriangleMesh m;
  std::map<std::array<uint32_t, 3>, uint32_t> index;  // lattice point (0..n per axis) -> vertex
  auto vertex = [&](std::array<uint32_t, 3> q) {
    auto [it, fresh] = index.try_emplace(q, uint32_t(m.vertices.size()));
    if (fresh) {
      auto at = [&](int a, double l, double h) { return q[a] == n ? h : l + (h - l) * q[a] / n; };
      m.vertices.push_back({at(0, lo.x, hi.x), at(1, lo.y, hi.y), at(2, lo.z, hi.z)});
    }
    return it->second;
  };
  for (int axis = 0; axis < 3; ++axis)
    for (uint32_t side = 0; side < 2; ++side) {
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      Point out{};
      (axis == 0 ? out.x : axis == 1 ? out.y : out.z) = side ? 1 : -1;
      for (uint32_t i = 0; i < n; ++i)
        for (uint32_t j = 0; j < n; ++j) {
          auto corner = [&](uint32_t di, uint32_t dj) {
            std::array<uint32_t, 3> q{};
            q[axis] = side * n;
            q[u] = i + di;
            q[v] = j + dj;
            return vertex(q);
          };
          const uint32_t a = corner(0, 0), b = corner(1, 0), c = corner(1, 1), d = corner(0, 1);
          add_oriented(m, a, b, c, out);
          add_oriented(m, a, c, d, out);
        }
    }
  return m;
}

inline TriangleMesh unit_cube() {
  return box_mesh({0, 0, 0}, {1, 1, 1});
}

// An icosahedron subdivided `levels` times (20 x 4^levels triangles), every vertex at distance r
// from the centre, normals outward.
inline TriangleMesh icosphere(double r, uint32_t levels, Point centre = {}) {
  const double t = (1 + std::sqrt(5.0)) / 2;
  std::vector<Point> v = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0},
                          {0, -1, t}, {0, 1, t}, {0, -1, -t}, {0, 1, -t},
                          {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  std::vector<std::array<uint32_t, 3>> f = {
      {0, 11, 5},  {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
      {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
      {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  auto unit = [](Point p) { return (1 / mesh::length(p)) * p; };
  for (auto& p : v) p = unit(p);
  for (uint32_t l = 0; l < levels; ++l) {
    std::map<std::pair<uint32_t, uint32_t>, uint32_t> mid;
    auto middle = [&](uint32_t a, uint32_t b) {
      auto [it, fresh] = mid.try_emplace({std::min(a, b), std::max(a, b)}, uint32_t(v.size()));
      if (fresh) v.push_back(unit(0.5 * (v[a] + v[b])));
      return it->second;
    };
    std::vector<std::array<uint32_t, 3>> g;
    for (const auto& tri : f) {
      const uint32_t ab = middle(tri[0], tri[1]), bc = middle(tri[1], tri[2]),
                     ca = middle(tri[2], tri[0]);
      g.push_back({tri[0], ab, ca});
      g.push_back({tri[1], bc, ab});
      g.push_back({tri[2], ca, bc});
      g.push_back({ab, bc, ca});
    }
    f = std::move(g);
  }
  TriangleMesh m;
  for (const auto& p : v) m.vertices.push_back(centre + r * p);
  for (const auto& tri : f) add_oriented(m, tri[0], tri[1], tri[2], m.vertices[tri[0]] - centre);
  return m;
}

inline void write_bytes(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
}

// Exact decimal text of a double (17 significant digits read back to the same bits).
inline std::string obj_text(const TriangleMesh& m) {
  std::string s = "# written by the masav mesh tests\no box\n";
  for (const Point& p : m.vertices) s += fmt::format("v {:.17g} {:.17g} {:.17g}\n", p.x, p.y, p.z);
  for (const auto& t : m.triangles) s += fmt::format("f {} {} {}\n", t[0] + 1, t[1] + 1, t[2] + 1);
  return s;
}

// header_count: the count written in the header (default: the true one).
inline std::string stl_binary(const TriangleMesh& m, int64_t header_count = -1) {
  std::string s(80, ' ');
  std::memcpy(s.data(), "masav test mesh", 15);
  const uint32_t count = header_count < 0 ? uint32_t(m.triangles.size()) : uint32_t(header_count);
  s.append(reinterpret_cast<const char*>(&count), 4);
  for (const auto& t : m.triangles) {
    float rec[12] = {};
    for (int k = 0; k < 3; ++k) {
      const Point p = m.vertices[t[k]];
      rec[3 + 3 * k] = float(p.x);
      rec[4 + 3 * k] = float(p.y);
      rec[5 + 3 * k] = float(p.z);
    }
    s.append(reinterpret_cast<const char*>(rec), sizeof(rec));
    s.append(2, '\0');
  }
  return s;
}

inline std::string stl_ascii(const TriangleMesh& m) {
  std::string s = "solid masav_test\n";
  for (const auto& t : m.triangles) {
    s += "  facet normal 0 0 0\n    outer loop\n";
    for (uint32_t k : t) {
      const Point p = m.vertices[k];
      s += fmt::format("      vertex {:.17g} {:.17g} {:.17g}\n", p.x, p.y, p.z);
    }
    s += "    endloop\n  endfacet\n";
  }
  return s + "endsolid masav_test\n";
}

// The signed distance to the box [lo, hi], negative inside.
inline double box_distance(Point p, Point lo, Point hi) {
  const double q[3] = {std::max(lo.x - p.x, p.x - hi.x), std::max(lo.y - p.y, p.y - hi.y),
                       std::max(lo.z - p.z, p.z - hi.z)};
  const double inside = std::max({q[0], q[1], q[2]});
  if (inside <= 0) return inside;
  double s = 0;
  for (double c : q) s += std::max(c, 0.0) * std::max(c, 0.0);
  return std::sqrt(s);
}

}  // namespace masav::test
