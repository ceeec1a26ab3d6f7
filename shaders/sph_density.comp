#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_KHR_shader_subgroup_shuffle : require
// Density (sph_density_term's kernel: spiky, or poly6 for the thesis model, Eq. 4.4) and
// pressure of each sorted particle over the neighbours
// within h in the 27 cells around cells[i], walked as 9 rows of 3 consecutive cells, and of
// their wall images (sph_wall_mirrors) when the particle is within h of a wall, added after the
// walk over the neighbours it kept. The candidates per invocation are capped (max_candidates)
// and an overflow is reported, never silently truncated. With neighbor_rows bound
// (p.neighbor_rows != 0), also records which candidates of each row lie within h, for
// sph_forces (kSphRowMaskBits in engine/kernels/sph_kernel_params.h). With the reach masks
// (SphReach, kSpecSphReach), also records which lie within the reach radius, or
// walks only those. With the neighbour state (kSpecSphState), also writes each
// particle's (x, rho | v, p / rho^2) record for sph_forces (kSphStateStride). Twin of
// sph::density_walk (engine/kernels/sph_kernels.h), which adds a neighbour's images with its own
// term.
#include "kernel_base.glsl"

// What the kernel only reads are uniform texel buffers (compute/vk_kernels.cpp): lavapipe fetches
// a texel with a gather, where it loads a storage buffer's element in a loop over the lanes.
layout(binding = 1) uniform samplerBuffer position_texels;     // rgba32f
layout(binding = 2) uniform usamplerBuffer cell_texels;        // r32ui
layout(binding = 3) uniform usamplerBuffer cell_start_texels;  // r32ui
layout(binding = 4) uniform usamplerBuffer cell_end_texels;    // r32ui
vec4 position_at(uint i) { return texelFetch(position_texels, int(i)); }
uint cell_at(uint i) { return texelFetch(cell_texels, int(i)).r; }
uint cell_start_at(uint cell) { return texelFetch(cell_start_texels, int(cell)).r; }
uint cell_end_at(uint cell) { return texelFetch(cell_end_texels, int(cell)).r; }
layout(std430, binding = 5) writeonly buffer Density { float density[]; };
layout(std430, binding = 6) writeonly buffer Pressure { float pressure[]; };
layout(std430, binding = 7) buffer Stats { uint stats[]; };
layout(binding = 8) uniform samplerBuffer velocity_texels;  // rgba32f
layout(std430, binding = 9) writeonly buffer NeighborState { vec4 neighbor_state[]; };
layout(std430, binding = 10) buffer ReachRows { uint reach_rows[]; };
layout(std430, binding = 11) writeonly buffer NeighborRows { uint neighbor_rows[]; };

// How the walk uses the reach masks (SphReach: none, record, walk). A constant rather than
// p.reach: lavapipe runs the code of a branch that no lane takes, so each use is a pipeline of
// its own and the others carry none of its cost.
layout(constant_id = kSpecSphReach) const uint SPH_REACH = 0u;
// Whether the call passes the neighbour state (and the velocities it holds).
layout(constant_id = kSpecSphState) const bool SPH_STATE = false;

#define SPH_MODEL_SPECIALIZED
#include "sph.glsl"
#include "sph_walk.glsl"
#include "sph_coop.glsl"
// The gathered rows' masks are the reach masks (the walk that visits only their bits).
uint neighbor_row_at(uint word) { return reach_rows[word]; }
#include "sph_row_walk.glsl"

MASAV_PUSH(SphStepLayout);

// What a walk adds up: the kernel sum, the neighbours within h, and the row's masks of its
// candidates within h and within the reach radius (SPH_REACH record).
struct Walk {
  float sum;
  uint within;
  uvec2 bits;
  uvec2 reach_bits;
};

// One chunk of a cooperative row: the cluster's kSphCoop candidates from `base`, rotated through
// its lanes. At rotation step k this lane examines candidate base + t, t = (lane + k) mod C, a
// constant per step, so whether it lies in the lane's row is two comparisons of t, and which
// neighbours it found is one word of bits t (C <= 32) that joins the row's mask once per chunk:
// lavapipe runs the per-candidate bit arithmetic of sph_mask_set on every lane of every step.
void coop_chunk(inout Walk w, vec3 xi, uint base, uvec2 u, uvec2 r) {
  const uint mine = base + sph_coop_lane();
  const vec3 xc = mine < u.y ? position_at(mine).xyz : vec3(0.0);
  const int lo = int(r.x) - int(base), hi = int(r.y) - int(base);  // the row: lo <= t < hi
  uint found = 0u, reach_found = 0u;
  for (uint k = 0u; k < kSphCoop; ++k) {
    LOOP_TICK();
    const vec3 xj = subgroupShuffle(xc, sph_coop_source(k));
    const uint t = (sph_coop_lane() + k) & (kSphCoop - 1u);
    const vec3 d = xi - xj;
    precise float r2 = d.x * d.x + d.y * d.y + d.z * d.z;  // unfused, as sph_density_term
    const bool in_row = int(t) >= lo && int(t) < hi;
    const bool near = in_row && r2 < p.h2;
    w.sum += in_row ? sph_density_term(r2, p) : 0.0;
    found |= near ? 1u << t : 0u;
    if (SPH_REACH == SphReach_record) reach_found |= in_row && r2 < p.reach2 ? 1u << t : 0u;
  }
  w.within += uint(bitCount(found));
  w.bits = sph_mask_or_shifted(w.bits, found, int(base) - int(r.x));
  if (SPH_REACH == SphReach_record)
    w.reach_bits = sph_mask_or_shifted(w.reach_bits, reach_found, int(base) - int(r.x));
}

// Candidate j of a row walked per lane (r: the row).
void lane_candidate(inout Walk w, vec3 xi, uint j, uvec2 r) {
  const vec3 xj = position_at(j).xyz;
  const vec3 d = xi - xj;
  precise float r2 = d.x * d.x + d.y * d.y + d.z * d.z;  // unfused, as sph_density_term
  const bool near = r2 < p.h2;
  w.sum += sph_density_term(r2, p);
  w.within += near ? 1u : 0u;
  w.bits = sph_mask_set(w.bits, j - r.x, near);
  if (SPH_REACH == SphReach_record)
    w.reach_bits = sph_mask_set(w.reach_bits, j - r.x, r2 < p.reach2);
}

// Stores row `row`'s two mask words of particle i in `rows` (neighbor_rows or reach_rows).
#define SPH_STORE_MASK(rows, row, bits)                    \
  {                                                        \
    rows[sph_mask_word(row, 0u, i, p.n)] = (bits).x;       \
    rows[sph_mask_word(row, 1u, i, p.n)] = (bits).y;       \
  }

// The walk over the reach masks (SPH_REACH walk): each lane's nine rows gathered with their
// recorded bits (or whole, where a row does not fit a mask), walked in one loop as sph_forces
// walks its masks (sph_row_walk.glsl), rows in order and ascending within a row: the sum adds
// the terms the whole walk adds, less the zeros beyond h. Each row's mask of neighbours within
// h is stored as the lane moves on from it; rows with nothing to walk store none. Returns the
// gathered rows (bit k: row k), which the wall images walk again.
uint walk_reach(inout Walk w, bool live, uint i, vec3 xi, ivec3 cc, inout uint candidates,
                inout bool overflow, out SphRowWalk rows[9]) {
  const uint gathered = sph_gather_rows(live, cc, i, true, p.dims, p.n, p.max_candidates,
                                        candidates, overflow, rows);
  const bool store = p.neighbor_rows != 0u && live;
  for (uint k = 0u; k < 9u; ++k) {
    LOOP_TICK();
    if (store && (gathered & (1u << k)) == 0u) SPH_STORE_MASK(neighbor_rows, k, uvec2(0u))
  }
  uint pending = gathered;
  SphRowWalk r = kSphNoRow;
  uint row = 9u;  // the row being walked
  uvec2 bits = uvec2(0u);
  while (pending != 0u || sph_row_left(r)) {
    LOOP_TICK();
    if (!sph_row_left(r)) {
      // A row walked whole (too long for a mask) stores no bits.
      if (store && row < 9u) SPH_STORE_MASK(neighbor_rows, row, r.end > r.first ? uvec2(0u) : bits)
      row = uint(findLSB(pending));
      SPH_NEXT_ROW(r, rows, pending)
      bits = uvec2(0u);
    }
    const uint j = sph_row_take(r);
    const vec3 d = xi - position_at(j).xyz;
    precise float r2 = d.x * d.x + d.y * d.y + d.z * d.z;  // unfused, as sph_density_term
    const bool near = r2 < p.h2;
    w.sum += sph_density_term(r2, p);
    w.within += near ? 1u : 0u;
    bits = sph_mask_set(bits, j - r.first, near);
  }
  if (store && row < 9u) SPH_STORE_MASK(neighbor_rows, row, r.end > r.first ? uvec2(0u) : bits)
  return gathered;
}

void main() {
  MASAV_LOAD_PUSH();
  // The range computed, [first, end) of the n (a rank's own particles); the others are only
  // read as neighbours.
  const uint i = p.first + flat_invocation_id();
  const bool live = i < p.end;
  uint candidates = 0u, within = 0u;
  uint rho_bits = 0u;  // a non-negative float's bits order like the float
  bool overflow = false, bad = false;
  // Every lane of the subgroup runs the row loops (the cooperative rows need them all);
  // lanes past n or whose rows leave the grid have empty ranges.
  vec3 xi = vec3(0.0);
  ivec3 cc = ivec3(-4);
  if (live) {
    xi = position_at(i).xyz;
    cc = sph_cell_coords(cell_at(i), p.dims);
  }
  SphMirrors mirrors = sph_wall_mirrors(xi, p);
  if (!live) mirrors.axes = 0u;
  const float own_images = mirrors.axes != 0u ? sph_own_image_density(xi, mirrors, p) : 0.0;
  const uvec3 dims = p.dims;
  // The neighbours' terms, row by row; each row's neighbours within h are kept (rows) for the
  // wall images below.
  SphRowWalk rows[9];
  uint pending = 0u;
  uint spent = 0u;
  Walk w = Walk(0.0, 0u, uvec2(0u), uvec2(0u));
  if (SPH_REACH == SphReach_walk)
    pending = walk_reach(w, live, i, xi, cc, candidates, overflow, rows);
  for (int dx = -1; SPH_REACH != SphReach_walk && dx <= 1; ++dx) {
    LOOP_TICK();
    for (int dy = -1; dy <= 1; ++dy) {
      LOOP_TICK();
      const uvec2 r = sph_lane_row(live, cc, dx, dy, dims, p.max_candidates, candidates, overflow);
      w.bits = uvec2(0u);  // this row's masks
      w.reach_bits = uvec2(0u);
      uvec2 u;
      if (sph_coop_row(r, spent, u)) {
        for (uint base = u.x; base < u.y; base += kSphCoop) {
          LOOP_TICK();
          coop_chunk(w, xi, base, u, r);
        }
      } else {
        for (uint j = r.x; j < r.y; ++j) {
          LOOP_TICK();
          lane_candidate(w, xi, j, r);
        }
      }
      const uint row = sph_row_index(dx, dy);
      const bool fits = sph_row_fits_mask(r);
      if (p.neighbor_rows != 0u && live)
        SPH_STORE_MASK(neighbor_rows, row, fits ? w.bits : uvec2(0u))
      if (SPH_REACH == SphReach_record && live)
        SPH_STORE_MASK(reach_rows, row, fits ? w.reach_bits : uvec2(0u))
      const SphRowWalk kept = sph_row_state(r, fits, w.bits);
      rows[row] = kept;
      if (sph_row_left(kept)) pending |= 1u << row;
    }
  }
  // The wall images of the neighbours within h (sph_wall_image_density), one loop over the rows
  // kept (the reach walk's rows, their bits a few more than the neighbours, each tested again),
  // after the neighbours' own terms: lavapipe runs every statement of a loop in every pass
  // whatever its lanes take, so the seven images, a square root each, cost a pass several times
  // the pair's, and this loop runs ~35 passes over the neighbours instead of the walk's ~200
  // over its candidates. Where the backend splits the walls off (sph_walls_near), a subgroup with
  // no lane within h of a wall makes one empty pass. A lane without walls adds nothing, so a
  // particle's density is the same whichever subgroup it shares.
  const bool walls_near = sph_walls_near(mirrors.axes);
  SphRowWalk wr = kSphNoRow;
  while (walls_near && (pending != 0u || sph_row_left(wr))) {
    LOOP_TICK();
    if (!sph_row_left(wr)) SPH_NEXT_ROW(wr, rows, pending)
    const uint j = sph_row_take(wr);
    const vec3 xj = position_at(j).xyz;
    const vec3 d = xi - xj;
    precise float r2 = d.x * d.x + d.y * d.y + d.z * d.z;  // unfused, as in the walk
    if (r2 < p.h2 && j != i && mirrors.axes != 0u)
      w.sum += sph_wall_image_density(xi, xj, mirrors, p);
  }
  const float sum = w.sum;
  within = w.within;
  if (live) {
    const float rho = p.density * sum + own_images;
    const float pr = sph_pressure_of(rho, p);
    density[i] = rho;
    pressure[i] = pr;
    if (SPH_STATE) {
      neighbor_state[kSphStateStride * i] = vec4(xi, rho);
      neighbor_state[kSphStateStride * i + 1u] =
          vec4(texelFetch(velocity_texels, int(i)).xyz, sph_pressure_over_rho2(pr, rho));
    }
    bad = !sph_finite(rho) || !sph_finite(pr);
    rho_bits = bad ? 0u : floatBitsToUint(max(rho, 0.0));
  }
  // One atomic per subgroup and statistic.
  const uint max_cand = subgroupMax(candidates);
  const uint max_within = subgroupMax(within);
  const uint over = subgroupMax(overflow ? ~i : 0u);
  const uint nonfinite = subgroupMax(bad ? ~i : 0u);
  const uint max_rho = subgroupMax(rho_bits);
  if (subgroupElect()) {
    atomicMax(stats[kSphStatMaxCandidates], max_cand);
    atomicMax(stats[kSphStatMaxNeighbors], max_within);
    atomicMax(stats[kSphStatMaxDensity], max_rho);
    if (over != 0u) atomicMax(stats[kSphStatOverflow], over);
    if (nonfinite != 0u) atomicMax(stats[kSphStatNonFinite], nonfinite);
  }
  report_loop_ticks();
}
