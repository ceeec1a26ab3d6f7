#include "engine/volume/brick_skip.h"

#include "engine/kernels/atom_checks.h"

namespace masav::volume {

void fill_bricks(Backend& b, const VolumeBrickParams& p, const Buffer<Real>& volume,
                 const Buffer<Real4>& tf, Buffer<Real4>& bricks, uint32_t radius) {
  b.volume_bricks(p, volume, tf, bricks);
  if (radius <= 1) return;  // volume_bricks' stride is 1
  const UVec3 nb = brick_dims(p.volume, p.brick);
  BrickSkipParams s;
  s.bricks = nb;
  s.radius = radius;
  // Two passes' distances; the third writes bricks[].w.
  Buffer<uint32_t> distances =
      b.create<uint32_t>(2 * size_t(nb.x) * nb.y * nb.z, "brick skip distances");
  for (uint32_t axis = 0; axis < 3; ++axis) {
    s.axis = axis;
    b.volume_brick_skip(s, bricks, distances);
  }
}

}  // namespace masav::volume
