// Voxelization, brick ranges and ray casting on Vulkan (shaders/voxelize_*.comp,
// volume_bricks.comp, raymarch.comp).
#include "compute/vk_backend.h"
#include "engine/atom/atom_checks.h"

namespace masav::vk {
namespace {

struct AccumulatePush {
  float origin_inv_cell[4];
  uint32_t dims_n[4];
  float light_to_unit;
  uint32_t cells;
};
struct FinalizePush {
  uint32_t dims_cells[4];
  uint32_t particles;
  float s, t;
};
struct BrickPush {
  uint32_t dims_tf[4];
  uint32_t brick;
  float value_min, value_scale;
};
struct RaymarchPush {
  float eye_step[4];
  float forward_ref[4];
  float right_term[4];
  float up_vmin[4];
  float box_min_vscale[4];
  float box_max[4];
  uint32_t dims_tf[4];
  uint32_t wh_brick_flags[4];
};
static_assert(sizeof(RaymarchPush) == 128);

uint64_t groups_for(uint64_t items, uint32_t wg) { return (items + wg - 1) / wg; }

}  // namespace

void VulkanBackend::do_voxelize(const VoxelizeParams& p, uint64_t, const Buffer<Real4>& positions,
                             const Buffer<Real>& light, Buffer<Real>& probability,
                             Buffer<Real>& mean_light, Buffer<Real>& sample) {
  const char* k = "voxelize";
  const uint64_t cells = grid_cell_count(p.grid);
  auto tallies = scratch("voxelize tallies", (3 * cells + 1) * 4);
  stream_.fill(tallies, 0);
  const GridParams& g = p.grid;
  const AccumulatePush acc{{g.origin.x, g.origin.y, g.origin.z, g.inv_cell},
                           {g.dims.x, g.dims.y, g.dims.z, g.n},
                           p.light_to_unit,
                           uint32_t(cells)};
  run({"voxelize_accumulate", 3, sizeof acc, {}},
      {alloc(positions.impl(), k), alloc(light.impl(), k), tallies}, &acc,
      groups_for(g.n, options_.workgroup_size));
  const FinalizePush fin{{g.dims.x, g.dims.y, g.dims.z, uint32_t(cells)}, g.n, p.s, p.t};
  run({"voxelize_finalize", 4, sizeof fin, {}},
      {tallies, alloc(probability.impl(), k), alloc(mean_light.impl(), k),
       alloc(sample.impl(), k)},
      &fin, groups_for(cells, options_.workgroup_size));
}

void VulkanBackend::do_volume_bricks(const VolumeBrickParams& p, uint64_t, const Buffer<Real>& volume,
                                  const Buffer<Real4>& tf, Buffer<Real4>& bricks) {
  const char* k = "volume_bricks";
  const UVec3 nb = brick_dims(p.volume, p.brick);
  const BrickPush push{{p.volume.dims.x, p.volume.dims.y, p.volume.dims.z, p.tf_size},
                       p.brick,
                       p.volume.value_min,
                       1.0f / (p.volume.value_max - p.volume.value_min)};
  run({k, 3, sizeof push, {}}, {alloc(volume.impl(), k), alloc(tf.impl(), k), alloc(bricks.impl(), k)},
      &push, groups_for(uint64_t(nb.x) * nb.y * nb.z, options_.workgroup_size));
}

void VulkanBackend::do_raymarch(const RaymarchParams& p, uint64_t, const Buffer<Real>& volume,
                             const Buffer<Real4>& tf, const Buffer<Real4>& bricks,
                             Buffer<Real4>& image) {
  const char* k = "raymarch";
  const volume::RayCamera c = make_ray_camera(p);
  const VolumeDesc& v = p.volume;
  const uint32_t flags = (p.mode == Compositing::lerp ? 1u : 0u) | (p.skip_empty ? 2u : 0u);
  const RaymarchPush push{{c.eye[0], c.eye[1], c.eye[2], p.step},
                          {c.forward[0], c.forward[1], c.forward[2], p.reference_step},
                          {c.right[0], c.right[1], c.right[2], p.termination_alpha},
                          {c.up[0], c.up[1], c.up[2], v.value_min},
                          {v.box_min.x, v.box_min.y, v.box_min.z, c.value_scale},
                          {v.box_max.x, v.box_max.y, v.box_max.z, 0.0f},
                          {v.dims.x, v.dims.y, v.dims.z, p.tf_size},
                          {p.width, p.height, p.brick, flags}};
  run({k, 4, sizeof push, {}},
      {alloc(volume.impl(), k), alloc(tf.impl(), k), alloc(bricks.impl(), k),
       alloc(image.impl(), k)},
      &push, groups_for(uint64_t(p.width) * p.height, options_.workgroup_size));
}

}  // namespace masav::vk
