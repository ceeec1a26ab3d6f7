// The multi-pass atom kernels CUDA runs itself, host side: scatter_table (photons, then the
// fixed-point tallies turned into fractions) and voxelize (accumulate, then finalize per cell).
#include "cuda_ref/atom_launch.h"
#include "cuda_ref/cuda_backend.h"
#include "cuda_ref/cuda_launch.h"
#include "engine/kernels/scatter_math.h"

namespace masav::cuda {
namespace {

template <class T>
T* as(void* p) {
  return static_cast<T*>(p);
}

}  // namespace

void CudaBackend::run_own(const KernelArgs<KernelId::scatter_table>& a) {
  auto& [p, items_, table, hits] = a;
  const char* k = "scatter_table";
  const uint32_t entries_per_row = p.bins + kScatterExtras;
  const uint64_t entries = uint64_t(p.rows) * entries_per_row;
  auto* tallies = as<unsigned long long>(scratch("scatter_table", entries * 8, k));
  auto* h = as<uint32_t>(ptr(hits.impl(), k));
  zero(tallies, entries * 8, k);
  zero(h, entries * 4, k);
  const uint32_t threads = 128;  // photons diverge: small blocks keep the shared tallies busy
  const uint32_t blocks_per_row = (p.photons_per_row + threads - 1) / threads;
  launched(launch::scatter_table(stream_, grid_for(uint64_t(p.rows) * blocks_per_row, k), threads,
                                 p, blocks_per_row, tallies, h),
           k, "photons");
  const ScatterFinalizeParams fin{
      uint32_t(entries), float(1.0 / (double(1u << scatter::kFixedShift) * p.photons_per_row))};
  launched(launch::scatter_finalize(stream_, grid_for((entries + 255) / 256, k), fin, tallies,
                                    as<float>(ptr(table.impl(), k))),
           k, "finalize");
}

void CudaBackend::run_own(const KernelArgs<KernelId::voxelize>& a) {
  auto& [p, items_, positions, light, probability, mean_light, sample] = a;
  const char* k = "voxelize";
  const uint64_t cells = grid_cell_count(p.grid);
  auto* counts = as<uint32_t>(scratch("voxelize counts", (cells + 1) * 4, k));
  auto* sums = as<unsigned long long>(scratch("voxelize sums", cells * 8, k));
  zero(counts, (cells + 1) * 4, k);
  zero(sums, cells * 8, k);
  launched(launch::voxelize_accumulate(stream_, grid_for_items(p.grid.n, k), p,
                                       as<const float4>(ptr(positions.impl(), k)),
                                       as<const float>(ptr(light.impl(), k)), counts, sums),
           k, "accumulate");
  launched(launch::voxelize_finalize(stream_, grid_for_items(cells, k), p, counts, sums,
                                     as<float>(ptr(probability.impl(), k)),
                                     as<float>(ptr(mean_light.impl(), k)),
                                     as<float>(ptr(sample.impl(), k))),
           k, "finalize");
}

}  // namespace masav::cuda
