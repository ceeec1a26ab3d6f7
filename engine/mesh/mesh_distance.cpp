#include "engine/mesh/mesh_distance.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "engine/mesh/mesh_check.h"

namespace masav::mesh {
namespace {

constexpr uint32_t kLeafTriangles = 4;

double box_distance2(Point p, const Bounds& b) {
  const double dx = std::max({b.lo.x - p.x, 0.0, p.x - b.hi.x});
  const double dy = std::max({b.lo.y - p.y, 0.0, p.y - b.hi.y});
  const double dz = std::max({b.lo.z - p.z, 0.0, p.z - b.hi.z});
  return dx * dx + dy * dy + dz * dz;
}

// The angle between u and v, from atan2 (accurate for angles near 0 and pi, unlike acos).
double angle_between(Point u, Point v) {
  return std::atan2(length(cross(u, v)), dot(u, v));
}

}  // namespace

// Ericson, Real-Time Collision Detection (2005), section 5.1.5, ClosestPtPointTriangle: the
// Voronoi regions of the corners, then of the edges, then the face, tested with the dot products
// d1..d6 and the barycentric numerators va, vb, vc.
ClosestPoint closest_point_on_triangle(Point p, Point a, Point b, Point c) {
  const Point ab = b - a, ac = c - a, ap = p - a;
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return {a, Feature::corner0};
  const Point bp = p - b;
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return {b, Feature::corner1};
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return {a + (d1 / (d1 - d3)) * ab, Feature::edge0};
  const Point cp = p - c;
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return {c, Feature::corner2};
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return {a + (d2 / (d2 - d6)) * ac, Feature::edge2};
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0)
    return {b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b), Feature::edge1};
  const double denom = 1 / (va + vb + vc);
  return {a + (vb * denom) * ab + (vc * denom) * ac, Feature::face};
}

MeshDistance::MeshDistance(const TriangleMesh& m, std::string_view where) : mesh_(m) {
  const std::vector<uint32_t> opposite = edge_neighbours(m, where);  // throws unless closed
  const size_t n = m.triangles.size();
  face_normal_.resize(n);
  edge_normal_.resize(3 * n);
  vertex_normal_.assign(m.vertices.size(), Point{});
  std::vector<Point> centroid(n);
  for (size_t t = 0; t < n; ++t) {
    const auto& tri = m.triangles[t];
    const Point a = m.vertices[tri[0]], b = m.vertices[tri[1]], c = m.vertices[tri[2]];
    const Point nrm = cross(b - a, c - a);
    face_normal_[t] = (1 / length(nrm)) * nrm;  // not zero: the check refuses zero-area triangles
    centroid[t] = (1.0 / 3) * (a + b + c);
  }
  for (size_t t = 0; t < n; ++t) {
    const auto& tri = m.triangles[t];
    for (int k = 0; k < 3; ++k) {
      edge_normal_[3 * t + k] = face_normal_[t] + face_normal_[opposite[3 * t + k] / 3];
      const Point v = m.vertices[tri[k]];
      const double w =
          angle_between(m.vertices[tri[(k + 1) % 3]] - v, m.vertices[tri[(k + 2) % 3]] - v);
      vertex_normal_[tri[k]] = vertex_normal_[tri[k]] + w * face_normal_[t];
    }
  }
  order_.resize(n);
  for (uint32_t t = 0; t < n; ++t) order_[t] = t;
  nodes_.reserve(2 * (n / kLeafTriangles + 1));
  nodes_.emplace_back();
  build_node(0, 0, uint32_t(n), centroid);
}

void MeshDistance::build_node(uint32_t node, uint32_t begin, uint32_t end,
                              const std::vector<Point>& centroid) {
  Bounds box{mesh_.vertices[mesh_.triangles[order_[begin]][0]],
             mesh_.vertices[mesh_.triangles[order_[begin]][0]]};
  Bounds cbox{centroid[order_[begin]], centroid[order_[begin]]};
  for (uint32_t i = begin; i < end; ++i) {
    for (uint32_t v : mesh_.triangles[order_[i]]) {
      const Point p = mesh_.vertices[v];
      box.lo = {std::min(box.lo.x, p.x), std::min(box.lo.y, p.y), std::min(box.lo.z, p.z)};
      box.hi = {std::max(box.hi.x, p.x), std::max(box.hi.y, p.y), std::max(box.hi.z, p.z)};
    }
    const Point c = centroid[order_[i]];
    cbox.lo = {std::min(cbox.lo.x, c.x), std::min(cbox.lo.y, c.y), std::min(cbox.lo.z, c.z)};
    cbox.hi = {std::max(cbox.hi.x, c.x), std::max(cbox.hi.y, c.y), std::max(cbox.hi.z, c.z)};
  }
  nodes_[node].box = box;
  if (end - begin <= kLeafTriangles) {
    nodes_[node].first = begin;
    nodes_[node].count = end - begin;
    return;
  }
  // Split at the median centroid along the widest axis of the centroids; ties broken by the
  // triangle number, so that the tree is one definite tree.
  const Point ext = cbox.hi - cbox.lo;
  const int ax = ext.x >= ext.y && ext.x >= ext.z ? 0 : ext.y >= ext.z ? 1 : 2;
  const uint32_t mid = begin + (end - begin) / 2;
  std::nth_element(order_.begin() + begin, order_.begin() + mid, order_.begin() + end,
                   [&](uint32_t l, uint32_t r) {
                     const double cl = hd::comp(centroid[l], ax), cr = hd::comp(centroid[r], ax);
                     return cl != cr ? cl < cr : l < r;
                   });
  const uint32_t left = uint32_t(nodes_.size());
  nodes_[node].first = left;
  nodes_[node].count = 0;
  nodes_.emplace_back();
  nodes_.emplace_back();
  build_node(left, begin, mid, centroid);
  build_node(left + 1, mid, end, centroid);
}

void MeshDistance::test(Point p, uint32_t t, Nearest& best) const {
  const auto& tri = mesh_.triangles[t];
  const ClosestPoint q = closest_point_on_triangle(p, mesh_.vertices[tri[0]],
                                                   mesh_.vertices[tri[1]], mesh_.vertices[tri[2]]);
  const Point d = p - q.point;
  const double d2 = dot(d, d);
  if (d2 < best.distance2 || (d2 == best.distance2 && t < best.triangle)) best = {t, d2, q};
}

MeshDistance::Nearest MeshDistance::nearest(Point p, uint32_t hint) const {
  Nearest best{kNoHint, std::numeric_limits<double>::infinity(), {}};
  if (hint < mesh_.triangles.size()) test(p, hint, best);
  // Depth-first, the nearer child first; a box farther than the best is skipped, one at the same
  // distance is not (it may hold a lower-numbered triangle at that distance).
  uint32_t stack[128];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& node = nodes_[stack[--top]];
    if (box_distance2(p, node.box) > best.distance2) continue;
    if (node.count > 0) {
      for (uint32_t i = node.first; i < node.first + node.count; ++i) test(p, order_[i], best);
      continue;
    }
    const double dl = box_distance2(p, nodes_[node.first].box);
    const double dr = box_distance2(p, nodes_[node.first + 1].box);
    const uint32_t near = dl <= dr ? node.first : node.first + 1;
    const uint32_t far = dl <= dr ? node.first + 1 : node.first;
    if (std::max(dl, dr) <= best.distance2) stack[top++] = far;
    if (std::min(dl, dr) <= best.distance2) stack[top++] = near;
  }
  return best;
}

double MeshDistance::signed_distance(Point p, uint32_t* hint) const {
  const Nearest n = nearest(p, hint ? *hint : kNoHint);
  if (hint) *hint = n.triangle;
  const auto& tri = mesh_.triangles[n.triangle];
  const int f = int(n.closest.feature);
  const Point pseudo = f < 3   ? vertex_normal_[tri[f]]
                       : f < 6 ? edge_normal_[3 * n.triangle + (f - 3)]
                               : face_normal_[n.triangle];
  const double d = std::sqrt(n.distance2);
  return dot(p - n.closest.point, pseudo) < 0 ? -d : d;
}

}  // namespace masav::mesh
