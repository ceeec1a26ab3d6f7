// scatter_table on the CPU reference: photons in double precision, tallied in double per block
// of photons and added up in block order, so the table does not depend on the thread count.
#include <vector>

#include "engine/cpu/cpu_backend.h"
#include "engine/kernels/atom_checks.h"
#include "engine/kernels/scatter_math.h"

namespace masav::cpu {

void CpuBackend::run_own(const KernelArgs<KernelId::scatter_table>& a) {
  auto& [p, items_, table, hits] = a;
  auto* tab = own(table.impl(), "scatter_table").as<double>();
  auto* cnt = own(hits.impl(), "scatter_table").as<uint32_t>();
  const uint32_t stride = p.bins + kScatterExtras;
  constexpr uint32_t kBlock = 2048;
  const uint32_t blocks_per_row = (p.photons_per_row + kBlock - 1) / kBlock;
  const size_t tasks = size_t(p.rows) * blocks_per_row;
  std::vector<double> part_w(tasks * stride, 0.0);
  std::vector<uint32_t> part_n(tasks * stride, 0);
  pool_.parallel_for(tasks, 1, [&](size_t b, size_t e) {
    for (size_t task = b; task < e; ++task) {
      const uint32_t row = uint32_t(task / blocks_per_row);
      const uint32_t first = uint32_t(task % blocks_per_row) * kBlock;
      const uint32_t last = std::min(first + kBlock, p.photons_per_row);
      const double tau = double(p.first_row + row) * double(p.tau_step);
      double* w = &part_w[task * stride];
      uint32_t* n = &part_n[task * stride];
      for (uint32_t ph = first; ph < last; ++ph) {
        const auto o = scatter::trace_photon<double>(p, tau, scatter::photon_stream(p, row, ph));
        w[o.entry] += o.weight;
        ++n[o.entry];
        if (o.entry < p.bins && o.scatterings == 0) {
          w[p.bins + kScatterUnscattered] += o.weight;
          ++n[p.bins + kScatterUnscattered];
        }
      }
    }
  });
  const double inv = 1.0 / double(p.photons_per_row);
  pool_.parallel_for(p.rows, 16, [&](size_t b, size_t e) {
    for (size_t row = b; row < e; ++row)
      for (uint32_t k = 0; k < stride; ++k) {
        double w = 0;
        uint32_t n = 0;
        for (uint32_t blk = 0; blk < blocks_per_row; ++blk) {
          w += part_w[(row * blocks_per_row + blk) * stride + k];
          n += part_n[(row * blocks_per_row + blk) * stride + k];
        }
        tab[row * stride + k] = w * inv;
        cnt[row * stride + k] = n;
      }
  });
}

}  // namespace masav::cpu
