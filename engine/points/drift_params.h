#pragma once
// Parameters of `drift_points`, the kernel of the `particles` demo scene: a Philox point cloud
// that drifts through a periodic box. Positions are a pure function of time (no state carried
// between frames), so any frame can be rendered, paused or replayed without stepping.
#include <cstdint>

#include "engine/core/buffer.h"
#include "engine/core/types.h"

namespace masav {

class DeviceApi;

// Point i, axis k, with u = start[4i + k] and w = direction[4i + k] (uniforms in [0, 1)):
//   f = u + (2w - 1) * speed * time_s,   position_k = box_lo_k + box_extent_k * (f - floor(f))
// and position.w = |velocity| in world units per second. `speed` is in box lengths per second
// along each axis (the fastest a point can move along one axis).
struct DriftParams {
  uint32_t n = 0;
  Vec3f box_lo{0, 0, 0};
  Vec3f box_extent{1, 1, 1};
  float speed = 0.05f;
  float time_s = 0.0f;
};

// Checked before any backend runs drift_points (engine/points/drift_checks.cpp).
void validate(const DeviceApi& dev, const DriftParams& p, const Buffer<float>& start,
              const Buffer<float>& direction, const Buffer<Real4>& positions);

}  // namespace masav
