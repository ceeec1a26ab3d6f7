// The hash-grid kernels the CPU reference runs itself: grid_cell_ranges (the tables cleared, then
// each run of a cell marked), grid_cell_offsets (a chunked scan) and gather (any element size).
// The per-point grid kernels run their shared bodies (engine/kernels/grid_body.h).
#include <algorithm>
#include <cstring>
#include <utility>
#include <vector>

#include "engine/cpu/cpu_elementwise.h"
#include "engine/kernels/kernel_checks.h"

namespace masav::cpu {

void CpuBackend::run_own(const KernelArgs<KernelId::grid_cell_ranges>& a) {
  auto& [g, items_, sorted_cells, cell_start, cell_end] = a;
  const uint32_t* c = body_pointer(sorted_cells);
  uint32_t* start = body_pointer(cell_start);
  uint32_t* end = body_pointer(cell_end);
  std::memset(start, 0, cell_start.size() * 4);
  std::memset(end, 0, cell_end.size() * 4);
  const uint32_t n = g.n;
  pool_.parallel_for(n, 8192, [&](size_t b, size_t e) {
    for (size_t i = b; i < e; ++i) {
      if (i == 0 || c[i] != c[i - 1]) start[c[i]] = uint32_t(i);
      if (i + 1 == n || c[i] != c[i + 1]) end[c[i]] = uint32_t(i + 1);
    }
  });
}

// Reduce-then-scan over contiguous chunks, as on the GPUs: each chunk sums its counts, a prefix
// over the chunk sums gives each chunk's first offset, then each chunk writes its runs.
void CpuBackend::run_own(const KernelArgs<KernelId::grid_cell_offsets>& a) {
  auto& [p, items_, counts, cell_start, cell_end] = a;
  const uint32_t* count = body_pointer(counts);
  uint32_t* start = body_pointer(cell_start);
  uint32_t* end = body_pointer(cell_end);
  const size_t cells = p.cell_count;
  const size_t chunks = std::min<size_t>(pool_.size() * 2, std::max<size_t>(1, cells / 65536));
  std::vector<uint32_t> first(chunks);
  pool_.run_chunks(cells, chunks, [&](size_t c, size_t b, size_t e) {
    uint32_t sum = 0;
    for (size_t i = b; i < e; ++i) sum += count[i];
    first[c] = sum;
  });
  uint32_t running = 0;
  for (uint32_t& f : first) running += std::exchange(f, running);
  pool_.run_chunks(cells, chunks, [&](size_t c, size_t b, size_t e) {
    uint32_t at = first[c];
    for (size_t i = b; i < e; ++i) {
      start[i] = at;
      at += count[i];
      end[i] = at;
    }
  });
}

void CpuBackend::run_own(const KernelArgs<KernelId::gather>& a) {
  auto& [p, items_, order, src, dst] = a;
  const uint32_t* o = body_pointer(order);
  const std::byte* s = static_cast<const CpuBuffer&>(src).data();
  std::byte* d = static_cast<CpuBuffer&>(dst).data();
  const size_t eb = elem_bytes(src.kind(), real_bytes()), src_count = src.count();
  CpuDiag diag;
  pool_.parallel_for(p.n, 8192, [&](size_t b, size_t e) {
    for (size_t i = b; i < e; ++i) {
      if (o[i] >= src_count) {
        diag.report(kDiagGatherIndexOutOfRange, uint32_t(i));
        std::memset(d + i * eb, 0, eb);
        continue;
      }
      std::memcpy(d + i * eb, s + size_t(o[i]) * eb, eb);
    }
  });
  if (diag.flags()) raise_diagnostics(*this, diag.flags(), diag.detail(), 0);
}

}  // namespace masav::cpu
