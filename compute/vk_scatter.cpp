// scatter_table on Vulkan: one photon per invocation, one tau row per workgroup, fixed-point
// integer tallies (shaders/scatter_table.comp), then a pass that turns them into fractions.
#include "compute/vk_backend.h"
#include "engine/atom/atom_checks.h"
#include "engine/kernels/scatter_math.h"

namespace masav::vk {
namespace {

struct ScatterPush {
  uint32_t rows, first_row, bins, photons_per_row;
  uint32_t groups_per_row, max_scatterings, from_centre, pad;
  float dir_tau_step[4];
  float g, albedo, threshold, pad2;
  uint32_t seed[2];
};
static_assert(sizeof(ScatterPush) == 72);
struct FinalizePush {
  uint32_t entries;
  float scale;
};

}  // namespace

void VulkanBackend::do_scatter_table(const ScatterTableParams& p, uint64_t, Buffer<Real>& table,
                                  Buffer<uint32_t>& hits) {
  const uint32_t entries_per_row = p.bins + kScatterExtras;
  const uint64_t entries = uint64_t(p.rows) * entries_per_row;
  auto tallies = scratch("scatter_table tallies", entries * 8);
  stream_.fill(tallies, 0);
  const auto& h = alloc(hits.impl(), "scatter_table");
  stream_.fill(h, 0);
  const uint32_t wg = options_.workgroup_size;
  const uint32_t groups_per_row = (p.photons_per_row + wg - 1) / wg;
  const ScatterPush push{p.rows,
                         p.first_row,
                         p.bins,
                         p.photons_per_row,
                         groups_per_row,
                         p.max_scatterings,
                         p.start == ScatterStart::centre ? 1u : 0u,
                         0,
                         {p.direction.x, p.direction.y, p.direction.z, p.tau_step},
                         p.g,
                         p.albedo,
                         p.weight_threshold,
                         0,
                         {uint32_t(p.seed), uint32_t(p.seed >> 32)}};
  run({"scatter_table", 2, sizeof push, {entries_per_row}}, {tallies, h}, &push,
      uint64_t(p.rows) * groups_per_row);
  const FinalizePush fin{uint32_t(entries),
                         float(1.0 / (double(1u << scatter::kFixedShift) * p.photons_per_row))};
  run({"scatter_finalize", 2, sizeof fin, {}}, {tallies, alloc(table.impl(), "scatter_table")},
      &fin, (entries + wg - 1) / wg);
}

}  // namespace masav::vk
