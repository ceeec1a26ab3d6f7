// DFSPH math: the GLSL twin of engine/kernels/dfsph_kernels.h (the spiky gradient, mirrored
// velocities, residual units) and the candidate walk the three DFSPH kernels share. Formulas and
// conventions are documented there; keep the two in step. The including shader defines
// position_at, cell_start_at, cell_end_at and neighbor_row_at, the push block `p` (DfsphLayout) and
// defines dfsph_visit(j, images), which the walk calls for each candidate (it tests the distance;
// `images`, a constant at each call: whether to add the wall images' terms).

#include "engine/kernels/dfsph_params.h"
#include "sph_row_walk.glsl"

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

// Twin of sph::dfsph_stopped: w, residual slot c.stop_slot (low, high), holds at most the
// stop units (the iteration before converged), so the call does nothing.
bool dfsph_stopped_at(uvec2 w, DfsphLayout c) {
  return w.y < c.stop_hi || (w.y == c.stop_hi && w.x <= c.stop_lo);
}

uint dfsph_residual_units(float r) {
  r = r < 1.0 ? r : 1.0;
  r = r > 0.0 ? r : 0.0;
  return uint(r * float(kDfsphResidualScale));
}

void dfsph_visit(uint j, bool images);

// Per lane, each row's neighbours from sph_density's masks (p.neighbor_rows != 0), or every
// candidate of a row too long for its mask or when there are no masks, in one loop over the nine
// rows (sph_row_walk.glsl). The loop is written twice, with and without the wall images
// (walls_near: some lane of the subgroup is within h of a wall): lavapipe runs every statement of
// a loop body in every pass, whatever its lanes take, so where the backend splits them
// (sph_walls_near) a subgroup away from the walls takes the copy without them (the other then
// makes one empty pass).
void dfsph_walk(bool live, uint i, ivec3 cc, bool walls_near, inout uint candidates,
                inout bool overflow) {
  SphRowWalk rows[9];
  uint pending = sph_gather_rows(live, cc, i, p.neighbor_rows != 0u, p.dims, p.n,
                                 p.max_candidates, candidates, overflow, rows);
  SphRowWalk w = kSphNoRow;
  while (walls_near && (pending != 0u || sph_row_left(w))) {
    LOOP_TICK();
    if (!sph_row_left(w)) SPH_NEXT_ROW(w, rows, pending)
    dfsph_visit(sph_row_take(w), true);
  }
  while (!walls_near && (pending != 0u || sph_row_left(w))) {
    LOOP_TICK();
    if (!sph_row_left(w)) SPH_NEXT_ROW(w, rows, pending)
    dfsph_visit(sph_row_take(w), false);
  }
}
