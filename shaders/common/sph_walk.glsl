// The 27-cell neighbour walk of the SPH kernels, by rows: the GLSL twin of sph::row_range
// (engine/kernels/sph_kernels.h). The including kernel declares cell_start[] and cell_end[].
// Sorted range of the row (x, y, z-1 .. z+1): 3 consecutive cell ids, contiguous points.
uvec2 sph_row_range(int x, int y, int z, uvec3 dims) {
  const int z0 = max(z - 1, 0);
  const int z1 = min(z + 1, int(dims.z) - 1);
  const uint base = (uint(x) * dims.y + uint(y)) * dims.z;
  uint first = 0u, last = 0u;
  bool found = false;
  for (int k = z0; k <= z1; ++k) {
    LOOP_TICK();
    const uint id = base + uint(k);
    const uint s = cell_start[id], e = cell_end[id];
    if (e > s) {
      if (!found) first = s;
      found = true;
      last = e;
    }
  }
  return uvec2(first, last);
}
