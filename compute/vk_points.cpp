// drift_points on Vulkan (shaders/drift_points.comp).
#include "compute/vk_backend.h"

namespace masav::vk {
namespace {

struct DriftPush {
  float lo_speed[4];
  float extent_time[4];
  uint32_t n;
};

}  // namespace

void VulkanBackend::do_drift_points(const DriftParams& p, uint64_t, const Buffer<float>& start,
                                 const Buffer<float>& direction, Buffer<Real4>& positions) {
  const DriftPush push{{p.box_lo.x, p.box_lo.y, p.box_lo.z, p.speed},
                       {p.box_extent.x, p.box_extent.y, p.box_extent.z, p.time_s},
                       p.n};
  const uint32_t wg = options_.workgroup_size;
  run({"drift_points", 3, sizeof push, {}},
      {alloc(start.impl(), "drift_points"), alloc(direction.impl(), "drift_points"),
       alloc(positions.impl(), "drift_points")},
      &push, (uint64_t(p.n) + wg - 1) / wg);
}

}  // namespace masav::vk
