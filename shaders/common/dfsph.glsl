// DFSPH math: the GLSL twin of engine/kernels/dfsph_kernels.h (the spiky gradient, mirrored
// velocities, residual units) and the candidate walk the three DFSPH kernels share. Formulas and
// conventions are documented there; keep the two in step. The including shader defines
// position_at, cell_start_at, cell_end_at and neighbor_row_at, the push block `p` (DfsphLayout) and
// defines dfsph_visit(j, images), which the walk calls for each candidate (it tests the distance;
// `images`, a constant at each call: whether to add the wall images' terms).

#include "engine/kernels/dfsph_params.h"

// m grad_i W_spiky for d = x_i - x_j, r^2 < h^2; 0 at r = 0.
vec3 dfsph_gradient(vec3 d, float r2, DfsphLayout c) {
  if (!(r2 > 0.0)) return vec3(0.0);
  const float r = sqrt(r2);
  const float u = 1.0 - r * c.inv_h;
  return (-(c.grad * u * u) / r) * d;
}

vec3 dfsph_mirror_velocity(vec3 v, uint s) {
  return mix(v, -v, bvec3((s & 1u) != 0u, (s & 2u) != 0u, (s & 4u) != 0u));
}

SphMirrors dfsph_mirrors(vec3 x, DfsphLayout c) {
  return sph_box_mirrors(x, vec3(c.lo[0], c.lo[1], c.lo[2]), vec3(c.hi[0], c.hi[1], c.hi[2]),
                         c.h2, c.walls);
}

// Whether xj's image in mirror set s lies within h of xi; its offset xi - image in d.
bool dfsph_image(vec3 xi, vec3 xj, SphMirrors m, uint s, float h2, out vec3 d, out float r2) {
  d = vec3(0.0);
  r2 = 0.0;
  if ((s & ~m.axes) != 0u) return false;
  d = sph_image_offset(xi, xj, m, s);
  r2 = dot(d, d);
  return r2 < h2;
}

uint dfsph_residual_units(float r) {
  r = r < 1.0 ? r : 1.0;
  r = r > 0.0 ? r : 0.0;
  return uint(r * float(kDfsphResidualScale));
}

void dfsph_visit(uint j, bool images);

// One row's walk state: the candidates [next, end) taken in order (a row too long for its mask,
// or no masks), then the set bits of `bits` from `first` (sph_density's mask).
struct DfsphRow {
  uint first, next, end;
  uvec2 bits;
};
bool dfsph_row_left(DfsphRow w) { return w.next < w.end || (w.bits.x | w.bits.y) != 0u; }
uint dfsph_row_take(inout DfsphRow w) {
  if (w.next < w.end) return w.next++;
  return w.first + sph_mask_take(w.bits);
}

// Per lane, each row's neighbours from sph_density's masks (p.neighbor_rows != 0), or every
// candidate of a row too long for its mask or when there are no masks. The rows are gathered
// first; then one loop walks them all, each lane moving to its next non-empty row as it finishes
// one, so that a subgroup iterates as often as its lane with the most candidates, not the sum over
// rows of each row's longest lane (lavapipe's loop cap counts the passes, and each pass costs the
// whole body); the order per lane is the rows' order. The loop is written twice, with and without
// the wall images (walls_near: some lane of the subgroup is within h of a wall): lavapipe runs
// every statement of a loop body in every pass, whatever its lanes take, so a subgroup away from
// the walls takes the copy without them (the other then makes one empty pass).
void dfsph_walk(bool live, uint i, ivec3 cc, bool walls_near, inout uint candidates,
                inout bool overflow) {
  DfsphRow rows[9];
  uint pending = 0u;  // bit k: row k has candidates
  for (int dx = -1; dx <= 1; ++dx) {
    LOOP_TICK();
    for (int dy = -1; dy <= 1; ++dy) {
      LOOP_TICK();
      const uvec2 r =
          sph_lane_row(live, cc, dx, dy, p.dims, p.max_candidates, candidates, overflow);
      const bool whole = p.neighbor_rows == 0u || !sph_row_fits_mask(r);
      const uint row = sph_row_index(dx, dy);
      DfsphRow w = DfsphRow(r.x, r.x, whole ? r.y : r.x, uvec2(0u));
      if (!whole && r.y > r.x)
        w.bits = uvec2(neighbor_row_at(sph_mask_word(row, 0u, i, p.n)),
                       neighbor_row_at(sph_mask_word(row, 1u, i, p.n)));
      rows[row] = w;
      if (dfsph_row_left(w)) pending |= 1u << row;
    }
  }
  DfsphRow w = DfsphRow(0u, 0u, 0u, uvec2(0u));
  while (walls_near && (pending != 0u || dfsph_row_left(w))) {
    LOOP_TICK();
    if (!dfsph_row_left(w)) {
      w = rows[findLSB(pending)];
      pending &= pending - 1u;
    }
    dfsph_visit(dfsph_row_take(w), true);
  }
  while (!walls_near && (pending != 0u || dfsph_row_left(w))) {
    LOOP_TICK();
    if (!dfsph_row_left(w)) {
      w = rows[findLSB(pending)];
      pending &= pending - 1u;
    }
    dfsph_visit(dfsph_row_take(w), false);
  }
}
