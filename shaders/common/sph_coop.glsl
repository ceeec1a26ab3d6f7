// The cooperative neighbour walk of the SPH kernels. Consecutive sorted particles share most of
// their 27 cells, so a cluster of C = SUBGROUP_MIN consecutive lanes, at most 32 (a power of two,
// at most the subgroup; sph_density holds the neighbours a lane finds in a chunk as one word of
// bits) walks each of the 9 rows together, over the union of its lanes' row ranges:
// each lane loads one candidate per chunk of C (contiguous loads, one per array and chunk instead
// of one per lane and candidate) and the chunk rotates through the cluster by shuffles whose
// pattern is fixed per step (lane + k mod C), which a SIMD CPU driver compiles to one register
// permute and a GPU to one shuffle. A lane counts only the candidates of its own row, so it sees
// exactly the neighbours of the per-lane walk (in rotated order within a chunk). A row whose
// union is much longer than the lanes' own ranges (lanes in distant cells: sparse fluid, the end
// of a column) is walked per lane instead.
//
// Loop budget: the union of a row is found without a loop (sph_coop_min and _max), and a
// cooperative row costs every lane the union's chunks (1 + C ticks each) instead of its own range;
// the extra over the shortest own range is charged to kSphCoopExtraTicks per invocation, so the
// worst case (max_candidates at its validated maximum plus this budget) stays under lavapipe's
// 65,535 iterations (kWalkLoopOverhead, engine/kernels/kernel_checks.h). The including kernel
// enables GL_KHR_shader_subgroup_shuffle.

const uint kSphCoopExtraTicks = 260u;
const uint kSphCoop = SUBGROUP_MIN < 32u ? SUBGROUP_MIN : 32u;
// Off: every row is walked per lane (the backend's choice: compute/sph_walk_choice.h).
layout(constant_id = kSpecSphCoopWalk) const bool SPH_COOP_WALK = true;

uint sph_coop_lane() { return gl_SubgroupInvocationID & (kSphCoop - 1u); }
// The lane of the cluster that holds, at rotation step k, the candidate this lane examines.
uint sph_coop_source(uint k) {
  return (gl_SubgroupInvocationID & ~(kSphCoop - 1u)) + ((sph_coop_lane() + k) & (kSphCoop - 1u));
}

// Minimum and maximum over the cluster (butterfly; clustered operations need a literal size),
// written out: with kSphCoop a constant once specialised, the steps it does not take fold away
// and no loop is left (lavapipe ran the loop's exit test and masks in every step).
uint sph_coop_min(uint v) {
  if (kSphCoop > 1u) v = min(v, subgroupShuffleXor(v, 1u));
  if (kSphCoop > 2u) v = min(v, subgroupShuffleXor(v, 2u));
  if (kSphCoop > 4u) v = min(v, subgroupShuffleXor(v, 4u));
  if (kSphCoop > 8u) v = min(v, subgroupShuffleXor(v, 8u));
  if (kSphCoop > 16u) v = min(v, subgroupShuffleXor(v, 16u));
  return v;
}
uint sph_coop_max(uint v) {
  if (kSphCoop > 1u) v = max(v, subgroupShuffleXor(v, 1u));
  if (kSphCoop > 2u) v = max(v, subgroupShuffleXor(v, 2u));
  if (kSphCoop > 4u) v = max(v, subgroupShuffleXor(v, 4u));
  if (kSphCoop > 8u) v = max(v, subgroupShuffleXor(v, 8u));
  if (kSphCoop > 16u) v = max(v, subgroupShuffleXor(v, 16u));
  return v;
}

// Whether the cluster walks row `r` (this lane's [first, last)) together, as the union
// [u.x, u.y); `spent` is the extra ticks charged so far (uniform over the cluster).
bool sph_coop_row(uvec2 r, inout uint spent, out uvec2 u) {
  u = uvec2(0u);
  if (!SPH_COOP_WALK) return false;
  const bool empty = r.y <= r.x;
  u = uvec2(sph_coop_min(empty ? 0xffffffffu : r.x), sph_coop_max(empty ? 0u : r.y));
  const uint own_min = sph_coop_min(empty ? 0u : r.y - r.x);
  if (u.y <= u.x) return false;  // no lane has candidates here
  const uint ticks = (u.y - u.x + kSphCoop - 1u) / kSphCoop * (kSphCoop + 1u);
  const uint extra = ticks > own_min ? ticks - own_min : 0u;
  if (extra > kSphCoopExtraTicks - spent) return false;
  spent += extra;
  return true;
}
