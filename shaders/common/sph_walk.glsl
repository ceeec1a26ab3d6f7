// The 27-cell neighbour walk of the SPH kernels, by rows, and the neighbour row masks: the GLSL
// twin of sph::row_range, sph::walk_rows and sph::RowMasks (engine/kernels/sph_kernels.h). The
// including kernel defines `uint cell_start_at(uint cell)` and `uint cell_end_at(uint cell)`.
// The includer enables GL_KHR_shader_subgroup_arithmetic.

// Whether a subgroup with no lane within h of a wall skips the wall images (the backend's choice
// per kernel, kSpecSphWallSplit: compute/sph_walk_choice.h): sph_forces and the DFSPH
// solves write their walk twice, with and without the images, and such a subgroup takes the copy
// without them; sph_density adds the images in a loop of its own after its walk, which such a
// subgroup skips. lavapipe runs every statement of a loop body in every pass, whatever its lanes
// take, so there the split saves the images' cost away from the walls. A GPU skips a branch that
// no lane of the subgroup takes, but its compiler may round two copies of a walk differently: a
// particle's sums would then depend on which particles share its subgroup, and a rank's
// particles, at other indices than in one process, would leave the one-process trajectory.
layout(constant_id = kSpecSphWallSplit) const bool SPH_WALL_SPLIT = true;

// Whether a lane's subgroup computes the wall images (axes: the lane's sph_wall_mirrors axes).
bool sph_walls_near(uint axes) { return !SPH_WALL_SPLIT || subgroupMax(axes) != 0u; }

// Sorted range of the row (x, y, z-1 .. z+1): 3 consecutive cell ids, contiguous points, from
// the first cell's start to the last one's end (the counting build's tables, where an empty cell
// reads [k, k): SphGridView::prefix_ranges); [0, 0) when all 3 are empty.
uvec2 sph_row_range(int x, int y, int z, uvec3 dims) {
  const int z0 = max(z - 1, 0);
  const int z1 = min(z + 1, int(dims.z) - 1);
  const uint base = (uint(x) * dims.y + uint(y)) * dims.z;
  const uint first = cell_start_at(base + uint(z0)), last = cell_end_at(base + uint(z1));
  return last > first ? uvec2(first, last) : uvec2(0u);
}

// This lane's range of row (dx, dy) around cell coordinates cc, counted against the candidate
// cap: empty for a dead lane, outside the grid, and from the row that would pass
// max_candidates on, which sets `overflow`.
uvec2 sph_lane_row(bool live, ivec3 cc, int dx, int dy, uvec3 dims, uint max_candidates,
                   inout uint candidates, inout bool overflow) {
  const int x = cc.x + dx, y = cc.y + dy;
  uvec2 r = uvec2(0u);
  if (live && !overflow && x >= 0 && x < int(dims.x) && y >= 0 && y < int(dims.y)) {
    r = sph_row_range(x, y, cc.z, dims);
    if (r.y - r.x > max_candidates - candidates) {
      overflow = true;
      r = uvec2(0u);
    }
    candidates += r.y - r.x;
  }
  return r;
}

// Row (dx, dy)'s index in walk order, and where word `word` (0 low, 1 high) of its mask for
// particle i lies in neighbor_rows (structure of arrays, kSphRowMaskWords words per particle).
uint sph_row_index(int dx, int dy) { return uint(3 * (dx + 1) + (dy + 1)); }
uint sph_mask_word(uint row, uint word, uint i, uint n) { return (2u * row + word) * n + i; }

bool sph_row_fits_mask(uvec2 r) { return r.y - r.x <= kSphRowMaskBits; }
// Sets bit b (of a row that fits) of a mask held as two words, if `on`.
uvec2 sph_mask_set(uvec2 m, uint b, bool on) {
  const uint bit = on ? 1u << (b & 31u) : 0u;
  return b < 32u ? uvec2(m.x | bit, m.y) : uvec2(m.x, m.y | bit);
}
// Sets bits off + t of a mask held as two words for the set bits t of `bits`; bits that land
// outside 0..63 are dropped.
uvec2 sph_mask_or_shifted(uvec2 m, uint bits, int off) {
  const uint s = uint(abs(off));
  const uint right = s < 32u ? bits >> s : 0u;
  const uint low = s < 32u ? bits << s : 0u;
  const uint carry = s == 0u || s >= 32u ? 0u : bits >> (32u - s);
  const uint high = s < 32u ? carry : (s < 64u ? bits << (s - 32u) : 0u);
  return off < 0 ? uvec2(m.x | right, m.y) : uvec2(m.x | low, m.y | high);
}
// The lowest set bit's index of a non-zero mask, cleared from it.
uint sph_mask_take(inout uvec2 m) {
  const bool low = m.x != 0u;
  const uint b = low ? uint(findLSB(m.x)) : 32u + uint(findLSB(m.y));
  m = low ? uvec2(m.x & (m.x - 1u), m.y) : uvec2(0u, m.y & (m.y - 1u));
  return b;
}
