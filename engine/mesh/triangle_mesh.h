#pragma once
// A triangle mesh in double precision: the shape of a boundary SPH reads from an OBJ or STL file
// (mesh_io.h), checks for a closed, outward-facing surface (mesh_check.h) and turns into a signed
// distance field (mesh_sdf.h). Vertices are shared: a triangle names three vertex indices, so that
// an edge of two triangles is the same pair of indices in both.
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "engine/kernels/hd_vec.h"

namespace masav::mesh {

// A point or vector of the mesh: the engine's shared vector type and its arithmetic
// (engine/kernels/hd_vec.h), which the kernels that read the field use too.
using Point = hd::V3<double>;
using hd::cross;
using hd::dot;
using hd::length;

// The most triangles a mesh may hold (and a file may declare): 10^7, about 0.7 GB in memory with
// the edge tables and the distance field's search tree.
inline constexpr uint64_t kMaxTriangles = 10'000'000;

struct Bounds {
  Point lo{}, hi{};
};

struct TriangleMesh {
  std::vector<Point> vertices;
  std::vector<std::array<uint32_t, 3>> triangles;

  // The smallest box holding every vertex ({0,0,0}, {0,0,0} for no vertices).
  Bounds bounds() const;
};

inline Bounds TriangleMesh::bounds() const {
  if (vertices.empty()) return {};
  Bounds b{vertices[0], vertices[0]};
  for (const Point& v : vertices) {
    b.lo = {std::fmin(b.lo.x, v.x), std::fmin(b.lo.y, v.y), std::fmin(b.lo.z, v.z)};
    b.hi = {std::fmax(b.hi.x, v.x), std::fmax(b.hi.y, v.y), std::fmax(b.hi.z, v.z)};
  }
  return b;
}

}  // namespace masav::mesh
