#pragma once
// A triangle mesh in double precision: the shape of a boundary SPH reads from an OBJ or STL file
// (mesh_io.h), checks for a closed, outward-facing surface (mesh_check.h) and turns into a signed
// distance field (mesh_sdf.h). Vertices are shared: a triangle names three vertex indices, so that
// an edge of two triangles is the same pair of indices in both.
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "engine/core/types.h"

namespace masav {

// Vec3d's arithmetic, beside the type so that argument-dependent lookup finds it everywhere.
inline Vec3d operator+(Vec3d a, Vec3d b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
inline Vec3d operator-(Vec3d a, Vec3d b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
inline Vec3d operator*(double s, Vec3d a) {
  return {s * a.x, s * a.y, s * a.z};
}

}  // namespace masav

namespace masav::mesh {

// The most triangles a mesh may hold (and a file may declare): 10^7, about 0.7 GB in memory with
// the edge tables and the distance field's search tree.
inline constexpr uint64_t kMaxTriangles = 10'000'000;

struct Bounds {
  Vec3d lo, hi;
};

struct TriangleMesh {
  std::vector<Vec3d> vertices;
  std::vector<std::array<uint32_t, 3>> triangles;

  // The smallest box holding every vertex ({0,0,0}, {0,0,0} for no vertices).
  Bounds bounds() const;
};

inline double dot(Vec3d a, Vec3d b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
inline Vec3d cross(Vec3d a, Vec3d b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline double length(Vec3d a) {
  return std::sqrt(dot(a, a));
}

inline Bounds TriangleMesh::bounds() const {
  if (vertices.empty()) return {};
  Bounds b{vertices[0], vertices[0]};
  for (const Vec3d& v : vertices) {
    b.lo = {std::fmin(b.lo.x, v.x), std::fmin(b.lo.y, v.y), std::fmin(b.lo.z, v.z)};
    b.hi = {std::fmax(b.hi.x, v.x), std::fmax(b.hi.y, v.y), std::fmax(b.hi.z, v.z)};
  }
  return b;
}

}  // namespace masav::mesh
