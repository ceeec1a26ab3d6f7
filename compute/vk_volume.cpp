// voxelize on Vulkan: an accumulate pass per particle into per-cell integer tallies, then a
// finalize pass per cell (shaders/voxelize_*.comp), both on VoxelizeParams.
#include "compute/vk_backend.h"

namespace masav::vk {

void VulkanBackend::run_own(const KernelArgs<KernelId::voxelize>& a) {
  auto& [p, items_, positions, light, probability, mean_light, sample] = a;
  const char* k = "voxelize";
  const uint64_t cells = grid_cell_count(p.grid);
  auto tallies = scratch("voxelize tallies", (3 * cells + 1) * 4);
  stream_.fill(tallies, 0);
  const uint32_t wg = options_.workgroup_size;
  run({"voxelize_accumulate", 3, sizeof p, {}},
      {alloc(positions.impl(), k), alloc(light.impl(), k), tallies}, &p, (p.grid.n + wg - 1) / wg);
  run({"voxelize_finalize", 4, sizeof p, {}},
      {tallies, alloc(probability.impl(), k), alloc(mean_light.impl(), k), alloc(sample.impl(), k)},
      &p, (cells + wg - 1) / wg);
}

}  // namespace masav::vk
