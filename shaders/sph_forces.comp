#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_KHR_shader_subgroup_shuffle : require
// Acceleration of each sorted particle: pressure (spiky gradient) and viscosity (its laplacian)
// per the pressure model, times the inverse mass (positions' w), plus gravity. One invocation
// per particle, no atomics in the neighbour loop; box walls through the neighbours' mirror
// images (sph_wall_mirrors). Neighbours are walked cooperatively
// (sph_coop.glsl) with p / rho^2 computed once per loaded candidate or, with neighbor_rows
// bound (p.neighbor_rows != 0), per lane over only the candidates sph_density found within h.
// The masked walk sums in ascending order within a row, the cooperative one in an order rotated
// within chunks, so the two differ by float rounding (the neighbours are the same). With the
// neighbour state (kSpecSphState: sph_density's (x, rho | v, p / rho^2) records), a
// candidate is one texel for the distance test and one more for a neighbour, in place of four
// arrays and a division. Twin of sph::force_at (engine/kernels/sph_kernels.h).
#include "kernel_base.glsl"

// What the kernel only reads are uniform texel buffers (compute/vk_kernels.cpp): lavapipe fetches
// a texel with a gather, where it loads a storage buffer's element in a loop over the lanes.
layout(binding = 1) uniform samplerBuffer position_texels;       // rgba32f
layout(binding = 2) uniform samplerBuffer velocity_texels;       // rgba32f
layout(binding = 3) uniform samplerBuffer density_texels;        // r32f
layout(binding = 4) uniform samplerBuffer pressure_texels;       // r32f
layout(binding = 5) uniform usamplerBuffer cell_texels;          // r32ui
layout(binding = 6) uniform usamplerBuffer cell_start_texels;    // r32ui
layout(binding = 7) uniform usamplerBuffer cell_end_texels;      // r32ui
layout(std430, binding = 8) writeonly buffer Accel { vec4 accel[]; };
layout(std430, binding = 9) buffer Stats { uint stats[]; };
layout(binding = 10) uniform samplerBuffer state_texels;          // rgba32f
layout(binding = 11) uniform usamplerBuffer neighbor_row_texels;  // r32ui
vec4 position_at(uint i) { return texelFetch(position_texels, int(i)); }
vec4 velocity_at(uint i) { return texelFetch(velocity_texels, int(i)); }
float density_at(uint i) { return texelFetch(density_texels, int(i)).r; }
float pressure_at(uint i) { return texelFetch(pressure_texels, int(i)).r; }
uint cell_at(uint i) { return texelFetch(cell_texels, int(i)).r; }
uint cell_start_at(uint cell) { return texelFetch(cell_start_texels, int(cell)).r; }
uint cell_end_at(uint cell) { return texelFetch(cell_end_texels, int(cell)).r; }
uint neighbor_row_at(uint word) { return texelFetch(neighbor_row_texels, int(word)).r; }

#define SPH_MODEL_SPECIALIZED
#include "sph.glsl"
#include "sph_walk.glsl"
#include "sph_coop.glsl"
#include "sph_row_walk.glsl"

// Whether the call passes sph_density's neighbour state (kSphStateStride): a constant, so that
// each form is a pipeline of its own and neither carries the other's loads.
layout(constant_id = kSpecSphState) const bool SPH_STATE = false;

// What the walk reads of candidate j: its position and density (the state's first record; the
// density is read only for a neighbour within h), then for a neighbour its velocity and
// p / rho^2 (the second).
vec4 candidate_at(uint j) {
  if (SPH_STATE) return texelFetch(state_texels, int(kSphStateStride * j));
  return vec4(position_at(j).xyz, 0.0);
}
struct Other {
  vec3 v;
  float rho, p_rho2;
};
Other neighbor_at(uint j, vec4 candidate) {
  if (SPH_STATE) {
    const vec4 vq = texelFetch(state_texels, int(kSphStateStride * j + 1u));
    return Other(vq.xyz, candidate.w, vq.w);
  }
  const float rho = density_at(j);
  return Other(velocity_at(j).xyz, rho, sph_pressure_over_rho2(pressure_at(j), rho));
}

MASAV_PUSH(SphStepLayout);

// The particle an invocation computes (sph::Neighbor): sorted index, position, velocity,
// density and p / rho^2.
struct Me {
  uint i;
  vec3 x, v;
  float rho, p_rho2;
  SphMirrors mirrors;  // no axes: no wall within h
};

// What the walk sums.
struct Sum {
  vec3 acc;
  uint neighbors, candidates;
  bool overflow;
};

// Candidate j's pair term, if it is another particle within h (the per-lane test), and, when
// `images` (a constant at each call), the terms of its wall images (also of the particle's own).
void add_candidate(Me me, uint j, inout Sum s, bool images) {
  const vec4 cj = candidate_at(j);
  const vec3 xj = cj.xyz;
  const vec3 d = me.x - xj;
  const float r2 = dot(d, d);
  if (!(r2 < p.h2) || (j == me.i && me.mirrors.axes == 0u)) return;
  const Other o = neighbor_at(j, cj);
  if (images && me.mirrors.axes != 0u)
    s.acc += sph_wall_image_accel(me.x, me.v, me.rho, me.p_rho2, xj, o.v, o.rho, o.p_rho2,
                                  me.mirrors, p);
  if (j == me.i) return;
  ++s.neighbors;
  s.acc += sph_pair_accel(me.v, me.rho, me.p_rho2, o.v, o.rho, o.p_rho2, d, r2, p);
}

// One chunk of a cooperative row: the cluster's kSphCoop candidates from `base` (position,
// velocity, density and p / rho^2 loaded once each), rotated through its lanes; their wall images
// when `images` (a constant at each call).
void coop_chunk(Me me, uint base, uvec2 u, uvec2 r, inout Sum s, bool images) {
  const uint mine = base + sph_coop_lane();
  vec3 xc = vec3(0.0), vc = vec3(0.0);
  float rc = 1.0, qc = 0.0;
  if (mine < u.y) {
    const vec4 c = candidate_at(mine);
    const Other o = neighbor_at(mine, c);
    xc = c.xyz;
    vc = o.v;
    rc = o.rho;
    qc = o.p_rho2;
  }
  for (uint k = 0u; k < kSphCoop; ++k) {
    LOOP_TICK();
    const uint src = sph_coop_source(k);
    const vec3 xj = subgroupShuffle(xc, src);
    const vec3 vj = subgroupShuffle(vc, src);
    const float rho_j = subgroupShuffle(rc, src);
    const float q_j = subgroupShuffle(qc, src);
    const uint j = base + ((sph_coop_lane() + k) & (kSphCoop - 1u));
    const vec3 d = me.x - xj;
    const float r2 = dot(d, d);
    const bool near = j >= r.x && j < r.y && r2 < p.h2;
    if (images && near && me.mirrors.axes != 0u)
      s.acc += sph_wall_image_accel(me.x, me.v, me.rho, me.p_rho2, xj, vj, rho_j, q_j,
                                    me.mirrors, p);
    if (near && j != me.i) {
      ++s.neighbors;
      s.acc += sph_pair_accel(me.v, me.rho, me.p_rho2, vj, rho_j, q_j, d, r2, p);
    }
  }
}

// Every lane runs the row loops (the cooperative rows need the whole subgroup); dead lanes have
// empty rows. Each loop over candidates is written twice, with and without the wall images
// (walls_near: some lane of the subgroup is within h of a wall): lavapipe runs every statement of
// a loop body in every pass, whatever its lanes take, and the seven images cost a pass several
// times the pair's, so where the backend splits them (sph_walls_near) a subgroup away from the
// walls takes the copy without them (the other then makes one empty pass).
void walk_cooperative(bool live, ivec3 cc, Me me, bool walls_near, inout Sum s) {
  uint spent = 0u;
  for (int dx = -1; dx <= 1; ++dx) {
    LOOP_TICK();
    for (int dy = -1; dy <= 1; ++dy) {
      LOOP_TICK();
      const uvec2 r = sph_lane_row(live, cc, dx, dy, p.dims, p.max_candidates, s.candidates,
                                   s.overflow);
      uvec2 u;
      if (sph_coop_row(r, spent, u)) {
        for (uint base = u.x; walls_near && base < u.y; base += kSphCoop) {
          LOOP_TICK();
          coop_chunk(me, base, u, r, s, true);
        }
        for (uint base = u.x; !walls_near && base < u.y; base += kSphCoop) {
          LOOP_TICK();
          coop_chunk(me, base, u, r, s, false);
        }
      } else {
        for (uint j = r.x; walls_near && j < r.y; ++j) {
          LOOP_TICK();
          add_candidate(me, j, s, true);
        }
        for (uint j = r.x; !walls_near && j < r.y; ++j) {
          LOOP_TICK();
          add_candidate(me, j, s, false);
        }
      }
    }
  }
}

// Candidate j's wall images, if it is another particle within h (walk_masked's second loop).
void add_images(Me me, uint j, inout Sum s) {
  const vec4 cj = candidate_at(j);
  const vec3 d = me.x - cj.xyz;
  if (!(dot(d, d) < p.h2) || j == me.i) return;
  const Other o = neighbor_at(j, cj);
  s.acc += sph_wall_image_accel(me.x, me.v, me.rho, me.p_rho2, cj.xyz, o.v, o.rho, o.p_rho2,
                                me.mirrors, p);
}

// Whether walk_masked adds the wall images after its direct terms or per neighbour inside its
// walk (the backend's choice, kSpecSphImagesAfter: compute/sph_walk_choice.h).
layout(constant_id = kSpecSphImagesAfter) const bool SPH_IMAGES_AFTER = false;

// Per lane, each row's set mask bits in ascending order, or every candidate of a row too long
// for its mask, in one loop over the nine rows (sph_row_walk.glsl). The distance test is
// repeated: a compiler that rounds r2 differently here than in sph_density can then drop a pair
// but never sum one beyond h. With SPH_IMAGES_AFTER the wall images come after the direct terms,
// in a second loop over the same rows that a subgroup with no lane near a wall skips
// (walls_near): the lane's own images, then its neighbours' in the walk's order, as
// sph::force_at and the CPU reference add them; each loop is written once. Otherwise the walk is
// written twice, as walk_cooperative's, with the images per neighbour in the copy that
// walls_near subgroups take.
void walk_masked(bool live, ivec3 cc, Me me, bool walls_near, inout Sum s) {
  SphRowWalk rows[9];
  const uint gathered = sph_gather_rows(live, cc, me.i, true, p.dims, p.n, p.max_candidates,
                                        s.candidates, s.overflow, rows);
  uint pending = gathered;
  SphRowWalk w = kSphNoRow;
  const bool inside = !SPH_IMAGES_AFTER && walls_near;
  while (inside && (pending != 0u || sph_row_left(w))) {
    LOOP_TICK();
    if (!sph_row_left(w)) SPH_NEXT_ROW(w, rows, pending)
    add_candidate(me, sph_row_take(w), s, true);
  }
  while (!inside && (pending != 0u || sph_row_left(w))) {
    LOOP_TICK();
    if (!sph_row_left(w)) SPH_NEXT_ROW(w, rows, pending)
    add_candidate(me, sph_row_take(w), s, false);
  }
  if (!SPH_IMAGES_AFTER || !walls_near) return;
  const bool images = live && me.mirrors.axes != 0u;
  if (images)
    s.acc += sph_wall_image_accel(me.x, me.v, me.rho, me.p_rho2, me.x, me.v, me.rho, me.p_rho2,
                                  me.mirrors, p);
  pending = images ? gathered : 0u;
  w = kSphNoRow;
  while (pending != 0u || sph_row_left(w)) {
    LOOP_TICK();
    if (!sph_row_left(w)) SPH_NEXT_ROW(w, rows, pending)
    add_images(me, sph_row_take(w), s);
  }
}

void main() {
  MASAV_LOAD_PUSH();
  // The range computed, [first, end) of the n (a rank's own particles); the others are only
  // read as neighbours.
  const uint i = p.first + flat_invocation_id();
  const bool live = i < p.end;
  float accel2 = 0.0;
  bool bad = false;
  vec4 pw = vec4(0.0);
  Me me = Me(i, vec3(0.0), vec3(0.0), 1.0, 0.0, SphMirrors(vec3(0.0), 0u));
  ivec3 cc = ivec3(-4);
  if (live) {
    pw = position_at(i);
    const vec4 ci = candidate_at(i);
    const Other o = neighbor_at(i, ci);
    me.x = ci.xyz;
    me.v = o.v;
    me.rho = o.rho;
    me.p_rho2 = o.p_rho2;
    cc = sph_cell_coords(cell_at(i), p.dims);
    me.mirrors = sph_wall_mirrors(me.x, p);
  }
  Sum s = Sum(vec3(0.0), 0u, 0u, false);
  const bool walls_near = sph_walls_near(me.mirrors.axes);
  if (p.neighbor_rows != 0u) {
    walk_masked(live, cc, me, walls_near, s);
  } else {
    walk_cooperative(live, cc, me, walls_near, s);
  }
  if (live) {
    const vec3 a = sph_total_accel(s.acc, pw.w, p);
    accel[i] = vec4(a, float(s.neighbors));
    bad = !sph_finite(a);
    if (!bad && pw.w > 0.0) accel2 = dot(a, a);
  }
  const uint max_cand = subgroupMax(s.candidates);
  const uint over = subgroupMax(s.overflow ? ~i : 0u);
  const uint nonfinite = subgroupMax(bad ? ~i : 0u);
  const uint max_a2 = subgroupMax(floatBitsToUint(accel2));
  if (subgroupElect()) {
    atomicMax(stats[kSphStatMaxCandidates], max_cand);
    atomicMax(stats[kSphStatMaxAccel2], max_a2);
    if (over != 0u) atomicMax(stats[kSphStatOverflow], over);
    if (nonfinite != 0u) atomicMax(stats[kSphStatNonFinite], nonfinite);
  }
  report_loop_ticks();
}
