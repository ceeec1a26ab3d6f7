#pragma once
// Exact signed distance from a point to a closed triangle mesh, in double precision. The closest
// point on each triangle is Ericson's (Real-Time Collision Detection, 2005, section 5.1.5); a
// bounding volume hierarchy over the triangles finds the nearest one by branch and bound. The sign
// is that of (p - q) . n, q the closest point and n the angle-weighted pseudo-normal of the
// feature q lies on (face, edge or vertex): J. A. Baerentzen and H. Aanaes, "Signed distance
// computation using the angle weighted pseudonormal", IEEE TVCG 11(3), 2005, 243-253, who prove
// that this sign is right for any closest point of a closed, oriented manifold. Negative inside.
#include <cstdint>
#include <string_view>
#include <vector>

#include "engine/mesh/triangle_mesh.h"

namespace masav::mesh {

// Where on a triangle (a, b, c) the closest point lies: corner k (0..2), the edge from corner k to
// corner k + 1 (edge0 + k), or the interior of the face.
enum class Feature : uint8_t { corner0, corner1, corner2, edge0, edge1, edge2, face };

struct ClosestPoint {
  Point point{};
  Feature feature = Feature::face;
};

ClosestPoint closest_point_on_triangle(Point p, Point a, Point b, Point c);

class MeshDistance {
 public:
  // Checks the mesh (mesh_check.h: closed, manifold, oriented, outward) and throws Error naming
  // `where` when it is not: only such a mesh has an inside. `m` must outlive this object.
  MeshDistance(const TriangleMesh& m, std::string_view where);

  struct Nearest {
    uint32_t triangle = 0;  // the lowest-numbered triangle at the smallest distance
    double distance2 = 0;   // squared (unsigned) distance
    ClosestPoint closest;
  };
  // `hint`, a triangle likely near p (the previous query's), only speeds the search: the result
  // is the same for any hint.
  Nearest nearest(Point p, uint32_t hint = kNoHint) const;
  double signed_distance(Point p, uint32_t* hint = nullptr) const;

  static constexpr uint32_t kNoHint = 0xffffffffu;

 private:
  struct Node {
    Bounds box;
    uint32_t first = 0;  // a leaf's first entry in order_, or an inner node's left child
    uint32_t count = 0;  // triangles in a leaf; 0 for an inner node (its right child is first + 1)
  };
  void build_node(uint32_t node, uint32_t begin, uint32_t end, const std::vector<Point>& centroid);
  void test(Point p, uint32_t t, Nearest& best) const;

  const TriangleMesh& mesh_;
  std::vector<Node> nodes_;
  std::vector<uint32_t> order_;       // triangle numbers, leaf by leaf
  std::vector<Point> face_normal_;    // unit, per triangle
  std::vector<Point> edge_normal_;    // per triangle edge 3 t + e: the sum of its two faces'
  std::vector<Point> vertex_normal_;  // per vertex: the angle-weighted sum of its faces'
};

}  // namespace masav::mesh
