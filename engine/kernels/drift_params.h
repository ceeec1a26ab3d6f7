// Parameters of `drift_points`, the kernel of the `particles` demo scene: a Philox point cloud
// that drifts through a periodic box. Positions are a pure function of time (no state carried
// between frames), so any frame can be rendered, paused or replayed without stepping. Shared by
// C++, CUDA and GLSL (engine/core/layout.h).
#ifndef MASAV_KERNELS_DRIFT_PARAMS_H
#define MASAV_KERNELS_DRIFT_PARAMS_H
#include "engine/core/layout.h"

MASAV_NAMESPACE_BEGIN

// Point i, axis k, with u = start[4i + k] and w = direction[4i + k] (uniforms in [0, 1)):
//   f = u + (2w - 1) * speed * time_s,   position_k = box_lo_k + box_extent_k * (f - floor(f))
// and position.w = |velocity| in world units per second. `speed` is in box lengths per second
// along each axis (the fastest a point can move along one axis).
MASAV_LAYOUT(DriftParams) {
  vec3 box_lo MASAV_INIT(vec3(0, 0, 0));
  float speed MASAV_INIT(0.05f);
  vec3 box_extent MASAV_INIT(vec3(1, 1, 1));
  float time_s MASAV_INIT(0.0f);
  uint n MASAV_INIT(0u);
};

MASAV_NAMESPACE_END

#ifdef __cplusplus
#include "engine/core/buffer.h"

namespace masav {

MASAV_LAYOUT_CHECK(DriftParams, 48, (box_lo, 0), (speed, 12), (box_extent, 16), (time_s, 28),
                   (n, 32))

class DeviceApi;
// Checked before any backend runs drift_points (engine/kernels/drift_checks.cpp).
void validate(const DeviceApi& dev, const DriftParams& p, const Buffer<float>& start,
              const Buffer<float>& direction, const Buffer<Real4>& positions);

}  // namespace masav
#endif
#endif
