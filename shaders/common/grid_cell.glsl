// Uniform-grid cell math and the 27-cell neighbour walk: the GLSL twin of
// engine/kernels/grid_cell.h. `precise` keeps one rounding per operation (no FMA), so a point
// lands in the same cell, and a distance compares the same, on every backend.

uint grid_axis_cell(float p, float origin, float inv_cell, uint dim) {
  precise float f = floor((p - origin) * inv_cell);
  if (!(f >= 0.0)) return 0u;  // also NaN
  if (f >= float(dim - 1u)) return dim - 1u;
  return uint(f);
}

// Thesis Eq. 4.2: HashValue = x * M * N + y * N + z.
uint grid_cell_id(uvec3 c, uvec3 dims) { return (c.x * dims.y + c.y) * dims.z + c.z; }

uvec3 grid_point_cell(vec3 p, vec3 origin, float inv_cell, uvec3 dims) {
  return uvec3(grid_axis_cell(p.x, origin.x, inv_cell, dims.x),
               grid_axis_cell(p.y, origin.y, inv_cell, dims.y),
               grid_axis_cell(p.z, origin.z, inv_cell, dims.z));
}

float grid_distance2(vec3 a, vec3 b) {
  precise vec3 d = b - a;
  precise float r = (d.x * d.x + d.y * d.y) + d.z * d.z;
  return r;
}

// The k-th (0..26) cell around c, x outermost and z innermost, as in the C++ helper. Returns
// false for cells outside the grid. Kernels loop k over 0..26 and then over
// [cell_start[id], cell_end[id]).
bool grid_neighbor_cell(uvec3 c, uvec3 dims, int k, out uint id) {
  const ivec3 n = ivec3(c) + ivec3(k / 9 - 1, (k / 3) % 3 - 1, k % 3 - 1);
  id = 0u;
  if (any(lessThan(n, ivec3(0))) || any(greaterThanEqual(n, ivec3(dims)))) return false;
  id = grid_cell_id(uvec3(n), dims);
  return true;
}
