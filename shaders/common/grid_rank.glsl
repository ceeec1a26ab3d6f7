// The rank pass of the counting sort by cell, shared by grid_rank_in_cell and grid_rank_and_move:
// the destination of the point in slot s is its cell's start plus the number of its cell's
// points with a smaller index. Twin of grid::rank_slot (engine/kernels/grid_body.h). The includer
// declares the buffers cells, unsorted, cell_start, cell_end and the CellRankParams push block.
bool rank_slot(uint s, uint outside_flag, uint overfull_flag, out uint point, out uint cell,
               out uint dest) {
  point = 0u;
  cell = 0u;
  dest = 0u;
  const uint i = unsorted[s];
  const uint c = i < p.n ? cells[i] : p.cell_count;
  if (c >= p.cell_count || s < cell_start[c] || s >= cell_end[c] || cell_end[c] > p.n) {
    report_diagnostic(outside_flag, s);
    return false;
  }
  const uint first = cell_start[c], last = cell_end[c];
  if (last - first > p.max_per_cell) {
    report_diagnostic(overfull_flag, c);
    return false;
  }
  uint rank = 0u;
  for (uint t = first; t < last; ++t) {
    LOOP_TICK();
    rank += unsorted[t] < i ? 1u : 0u;
  }
  point = i;
  cell = c;
  dest = first + rank;
  return true;
}
