// scatter_table on Vulkan: one photon per invocation, one tau row per workgroup, fixed-point
// integer tallies (shaders/scatter_table.comp), then a pass that turns them into fractions.
#include "compute/vk_backend.h"
#include "engine/kernels/scatter_math.h"
#include "shaders/spec_ids.h"

namespace masav::vk {

void VulkanBackend::run_own(const KernelArgs<KernelId::scatter_table>& a) {
  auto& [p, items_, table, hits] = a;
  const uint32_t entries_per_row = p.bins + kScatterExtras;
  const uint64_t entries = uint64_t(p.rows) * entries_per_row;
  auto tallies = scratch("scatter_table tallies", entries * 8);
  stream_.fill(tallies, 0);
  const auto& h = alloc(hits.impl(), "scatter_table");
  stream_.fill(h, 0);
  const uint32_t wg = options_.workgroup_size;
  const uint32_t groups_per_row = (p.photons_per_row + wg - 1) / wg;
  run({"scatter_table", 2, sizeof p, {{kSpecScatterEntries, entries_per_row}}}, {tallies, h}, &p,
      uint64_t(p.rows) * groups_per_row);
  const ScatterFinalizeParams fin{
      uint32_t(entries), float(1.0 / (double(1u << scatter::kFixedShift) * p.photons_per_row))};
  run({"scatter_finalize", 2, sizeof fin, {}}, {tallies, alloc(table.impl(), "scatter_table")},
      &fin, (entries + wg - 1) / wg);
}

}  // namespace masav::vk
