// The rank pass of the counting sort by cell, shared by grid_rank_in_cell and grid_rank_and_move:
// the destination of the point in slot s is its cell's start plus the number of its cell's
// points with a smaller index. Twin of grid::rank_slot (engine/kernels/grid_body.h). The includer
// defines `uint cell_at(uint)`, `uint unsorted_at(uint)`, `uint cell_start_at(uint)`,
// `uint cell_end_at(uint)` (texel buffers: see grid_rank_in_cell.comp) and the CellRankParams push
// block.
bool rank_slot(uint s, uint outside_flag, uint overfull_flag, out uint point, out uint cell,
               out uint dest) {
  point = 0u;
  cell = 0u;
  dest = 0u;
  const uint i = unsorted_at(s);
  const uint c = i < p.n ? cell_at(i) : p.cell_count;
  const uint first = c < p.cell_count ? cell_start_at(c) : 0u;
  const uint last = c < p.cell_count ? cell_end_at(c) : 0u;
  if (c >= p.cell_count || s < first || s >= last || last > p.n) {
    report_diagnostic(outside_flag, s);
    return false;
  }
  if (last - first > p.max_per_cell) {
    report_diagnostic(overfull_flag, c);
    return false;
  }
  uint rank = 0u;
  for (uint t = first; t < last; ++t) {
    LOOP_TICK();
    rank += unsorted_at(t) < i ? 1u : 0u;
  }
  point = i;
  cell = c;
  dest = first + rank;
  return true;
}
