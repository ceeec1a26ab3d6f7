#pragma once
// Whether a triangle mesh bounds a solid: what a signed distance needs to tell inside from
// outside. The mesh must be closed and manifold (every edge shared by exactly two triangles),
// consistently oriented (the two run the edge in opposite directions), free of zero-area
// triangles (which have no normal), and face outward (a positive enclosed volume). The first
// problem found is named with its triangles, vertex indices and positions, and what to do.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "engine/mesh/triangle_mesh.h"

namespace masav::mesh {

struct MeshCheck {
  uint64_t triangles = 0, vertices = 0;
  Bounds bounds;
  double area = 0;                 // the sum of the triangles' areas
  double volume = 0;               // enclosed, by the divergence theorem (meaningful when closed)
  uint64_t degenerate = 0;         // zero-area triangles
  uint64_t nonmanifold_edges = 0;  // edges of three or more triangles
  uint64_t open_edges = 0;         // edges of one triangle only
  uint64_t misoriented_edges = 0;  // edges two triangles run in the same direction
  std::string problem, remedy;     // the first problem, in the order above; "" when none
  bool closed() const { return problem.empty(); }
};

// Never throws for a problem of the mesh: it is reported in MeshCheck::problem.
MeshCheck check_mesh(const TriangleMesh& m);

// Edge e of triangle t runs from corner e to corner (e + 1) % 3 and is numbered 3 t + e. For every
// edge of a mesh that check_mesh finds closed, the number of the other triangle's edge along it;
// throws Error("", where, problem, remedy) for a mesh that is not.
std::vector<uint32_t> edge_neighbours(const TriangleMesh& m, std::string_view where);

}  // namespace masav::mesh
