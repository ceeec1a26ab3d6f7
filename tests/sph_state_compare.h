#pragma once
// Whether two SPH states hold the same positions and velocities bit for bit (x, y, z of each,
// particle by particle): the test of a trajectory that must not change.
#include "engine/sph/sph_simulation.h"

namespace masav::test {

inline bool same_state(const SphState& a, const SphState& b) {
  for (size_t i = 0; i < a.positions.size(); ++i) {
    const Vec4d &p = a.positions[i], &q = b.positions[i], &v = a.velocities[i],
                &w = b.velocities[i];
    if (p.x != q.x || p.y != q.y || p.z != q.z || v.x != w.x || v.y != w.y || v.z != w.z)
      return false;
  }
  return a.positions.size() == b.positions.size();
}

}  // namespace masav::test
