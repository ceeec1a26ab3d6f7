#pragma once
// A scalar volume and one raymarched frame of it on a backend: what the raymarch test files
// (test_volume.cpp, test_volume_clip_shade.cpp) render with.
#include <vector>

#include "engine/atom/preintegration.h"
#include "engine/kernels/atom_checks.h"
#include "engine/kernels/backend.h"

namespace masav::test {

struct Volume {
  VolumeDesc desc;
  std::vector<double> values;
};

// Bricks, the pre-integrated table and the image: everything rp needs, made on b.
inline std::vector<Vec4d> render(Backend& b, const RaymarchParams& rp, const Volume& vol,
                                 const std::vector<Vec4d>& tf) {
  auto v = b.create<Real>(vol.values.size(), "volume");
  b.upload(v, vol.values);
  auto t = b.create<Real4>(tf.size(), "tf");
  b.upload(t, tf);
  const UVec3 nb = brick_dims(rp.volume, rp.brick);
  auto bricks = b.create<Real4>(size_t(nb.x) * nb.y * nb.z, "bricks");
  b.volume_bricks({rp.volume, rp.brick, rp.tf_size}, v, t, bricks);
  auto img = b.create<Real4>(size_t(rp.width) * rp.height, "image");
  const Buffer<Real4> table = atom::upload_preintegrated(b, tf);
  b.raymarch(rp, v, t, bricks, img, &table);
  return b.download(img);
}

}  // namespace masav::test
