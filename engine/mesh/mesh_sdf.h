#pragma once
// A signed distance field of a closed triangle mesh on a regular grid: the implicit boundary an
// SPH particle samples (the distance to the wall and, from the gradient, its normal). The grid's
// nodes cover the mesh's bounds plus a padding on every side at a given spacing; each node holds
// the exact signed distance (mesh_distance.h), negative inside. Between nodes the field is
// trilinear. Built in double precision, and the same bits for any thread count: each node is
// computed on its own, and the search's result does not depend on the order it is done in.
#include <cstdint>
#include <string_view>
#include <vector>

#include "engine/core/types.h"
#include "engine/mesh/triangle_mesh.h"

namespace masav::mesh {

// The most nodes a field may hold: 2^24 (256^3, 128 MiB of doubles).
inline constexpr uint64_t kMaxSdfNodes = uint64_t(1) << 24;

struct SdfParams {
  double spacing = 0;    // between nodes, in the mesh's units; > 0
  double padding = 0;    // beyond the mesh's bounds on every side; >= 0
  uint32_t threads = 1;  // 0 = one per hardware thread; the field is the same for any count
};

// The grid of nodes for a mesh's bounds: origin = lo - padding, and on each axis the fewest
// nodes that reach hi + padding. Throws Error naming the parameter when the spacing or padding is
// not a finite number in range, or the grid would pass kMaxSdfNodes (with the spacing that fits).
struct SdfGrid {
  Point origin{};
  UVec3 dims;  // nodes per axis, each >= 2
  uint64_t nodes() const { return uint64_t(dims.x) * dims.y * dims.z; }
};
SdfGrid sdf_grid(const Bounds& b, const SdfParams& p);

struct SignedDistanceField {
  Point origin{};
  double spacing = 0;
  UVec3 dims;
  std::vector<double> values;  // x fastest, then y, then z

  uint64_t index(uint32_t i, uint32_t j, uint32_t k) const {
    return (uint64_t(k) * dims.y + j) * dims.x + i;
  }
  double node(uint32_t i, uint32_t j, uint32_t k) const { return values[index(i, j, k)]; }
  Point node_position(uint32_t i, uint32_t j, uint32_t k) const {
    return {origin.x + i * spacing, origin.y + j * spacing, origin.z + k * spacing};
  }
  // Trilinear between the nodes. A point outside the grid takes the value (and the gradient) at
  // the nearest point of the grid's box.
  double sample(Point p) const;
  // The gradient of the trilinear interpolant (per cell; at a face between cells, the cell on the
  // upper side's).
  Point gradient(Point p) const;
  double min_value() const;
  double max_value() const;
};

// Checks the mesh (closed, manifold, oriented outward: mesh_check.h) and the grid, then computes
// every node. Throws masav::Error naming `where`.
SignedDistanceField build_sdf(const TriangleMesh& m, const SdfParams& p,
                              std::string_view where = "mesh sdf");

}  // namespace masav::mesh
