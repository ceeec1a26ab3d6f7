// voxelize on Vulkan: an accumulate pass per particle into per-cell integer tallies, then a
// finalize pass per cell (shaders/voxelize_*.comp), both on VoxelizeParams. raymarch's first
// pass on a CPU device: its volume four voxels to a texel (shaders/raymarch_quads.comp).
#include "compute/raymarch_quads_choice.h"
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

bool raymarch_quads_wanted(const VulkanTuning& t, std::string_view device_type) {
  return resolve(t.raymarch_quads, device_type == "cpu");
}

std::shared_ptr<Allocation> VulkanBackend::raymarch_quads(const RaymarchLayout& layout,
                                                          const BufferImpl& volume) {
  const uint64_t voxels = uint64_t(layout.dims.x) * layout.dims.y * layout.dims.z;
  const uint64_t bytes = voxels * 16;
  if (!ray_quads_ || voxels == 0 || bytes > kMaxRayQuadBytes) return nullptr;
  // Exactly the volume's size: the texel view spans the whole allocation, and its texel count is
  // then the volume's, under the same device limit.
  if (!quads_ || quads_->bytes != bytes) {
    quads_ = allocate(ctx_, bytes, MemoryUse::device, "raymarch quads");
    quads_of_ = {};
  }
  const auto& source = alloc(volume, "raymarch");
  const QuadSource of{
      source->serial, source->writes, {layout.dims.x, layout.dims.y, layout.dims.z}};
  if (of == quads_of_) return quads_;
  const uint32_t wg = options_.workgroup_size;
  run({"raymarch_quads", 2, sizeof layout, {}, 0, {kTexelsR32f, kStorageBuffer}}, {source, quads_},
      &layout, (voxels + wg - 1) / wg, 0b10);
  quads_of_ = of;
  return quads_;
}

}  // namespace masav::vk
