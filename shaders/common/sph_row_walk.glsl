// The walk over sph_density's neighbour row masks (engine/kernels/sph_kernel_params.h,
// kSphRowMaskBits) that sph_forces and the DFSPH solves share. A lane first gathers its nine rows
// (sph_gather_rows); then one loop walks them all, the lane moving to its next non-empty row as it
// finishes one, so that a subgroup iterates as often as its lane with the most candidates, not the
// sum over rows of each row's longest lane (lavapipe's loop cap counts the passes, and each pass
// costs the whole body). The order per lane is the rows' order, ascending within a row, as in a
// row-by-row walk. The step of that loop (move to the next pending row when w has none left,
// SPH_NEXT_ROW, then take) is written out in each loop, not called: passed to a function, the
// nine rows are copied in every pass on lavapipe (sph_forces at 32,768 particles: 19 -> 49 ms).
// The includer includes sph_walk.glsl first and defines `uint neighbor_row_at(uint word)`, or
// defines SPH_ROWS_FROM_WALK (sph_density, which keeps the rows of its own walk) and gets no
// sph_gather_rows.

// One row's walk state: the candidates [next, end) in order (a row too long for its mask, or a
// walk without masks), then the set bits of `bits` from `first`.
struct SphRowWalk {
  uint first, next, end;
  uvec2 bits;
};
const SphRowWalk kSphNoRow = SphRowWalk(0u, 0u, 0u, uvec2(0u));

// Row r's walk: by its mask `bits` where `by_mask`, else every candidate in order.
SphRowWalk sph_row_state(uvec2 r, bool by_mask, uvec2 bits) {
  return SphRowWalk(r.x, r.x, by_mask ? r.x : r.y, by_mask ? bits : uvec2(0u));
}

// The loop's move to the lane's next row: w = rows[k], k the lowest bit of `pending`, which it
// clears. The rows are indexed by constants only, k picking one in a chain of selects: indexed by
// k, lavapipe keeps them in scratch memory and loads each field of the row lane by lane
// (sph_forces at 32,768 particles: 9.2 -> 8.0 ms).
#define SPH_NEXT_ROW(w, rows, pending)            \
  {                                               \
    const uint next_row_ = uint(findLSB(pending)); \
    pending &= pending - 1u;                      \
    w = rows[0];                                  \
    w = next_row_ == 1u ? rows[1] : w;            \
    w = next_row_ == 2u ? rows[2] : w;            \
    w = next_row_ == 3u ? rows[3] : w;            \
    w = next_row_ == 4u ? rows[4] : w;            \
    w = next_row_ == 5u ? rows[5] : w;            \
    w = next_row_ == 6u ? rows[6] : w;            \
    w = next_row_ == 7u ? rows[7] : w;            \
    w = next_row_ == 8u ? rows[8] : w;            \
  }

bool sph_row_left(SphRowWalk w) { return w.next < w.end || (w.bits.x | w.bits.y) != 0u; }
uint sph_row_take(inout SphRowWalk w) {
  if (w.next < w.end) return w.next++;
  return w.first + sph_mask_take(w.bits);
}

#ifndef SPH_ROWS_FROM_WALK
// This lane's nine rows around cell coordinates cc (sph_lane_row: counted against the candidate
// cap), each by its mask where `masks` and the row fits one; returns the set of rows (bit k: row
// k) with candidates.
uint sph_gather_rows(bool live, ivec3 cc, uint i, bool masks, uvec3 dims, uint n,
                     uint max_candidates, inout uint candidates, inout bool overflow,
                     out SphRowWalk rows[9]) {
  uint pending = 0u;
  for (int dx = -1; dx <= 1; ++dx) {
    LOOP_TICK();
    for (int dy = -1; dy <= 1; ++dy) {
      LOOP_TICK();
      const uvec2 r = sph_lane_row(live, cc, dx, dy, dims, max_candidates, candidates, overflow);
      const bool whole = !masks || !sph_row_fits_mask(r);
      const uint row = sph_row_index(dx, dy);
      uvec2 bits = uvec2(0u);
      if (!whole && r.y > r.x)
        bits = uvec2(neighbor_row_at(sph_mask_word(row, 0u, i, n)),
                     neighbor_row_at(sph_mask_word(row, 1u, i, n)));
      const SphRowWalk w = sph_row_state(r, !whole, bits);
      rows[row] = w;
      if (sph_row_left(w)) pending |= 1u << row;
    }
  }
  return pending;
}
#endif
