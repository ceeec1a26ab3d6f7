#pragma once
// A scalar volume and one raymarched frame of it on a backend: what the raymarch test files
// (test_volume.cpp, test_volume_clip_shade.cpp) render with.
#include <cmath>
#include <random>
#include <vector>

#include "engine/kernels/atom_checks.h"
#include "engine/kernels/backend.h"
#include "engine/volume/brick_skip.h"
#include "engine/volume/preintegration.h"

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
  volume::fill_bricks(b, {rp.volume, rp.brick, rp.tf_size}, v, t, bricks);
  auto img = b.create<Real4>(size_t(rp.width) * rp.height, "image");
  const Buffer<Real4> table = volume::upload_preintegrated(b, tf);
  b.raymarch(rp, v, t, bricks, img, &table);
  return b.download(img);
}

// A sparse cloud as voxelized particles leave it, 27 x 22 x 25 voxels: most 0, the rest scattered
// with values in [0, 1), a voxel being nonzero with probability `fill` at the centre falling off
// as a Gaussian (seeded: the same volume every run).
inline Volume sparse_cloud(double fill) {
  const UVec3 dims{27, 22, 25};
  Volume vol{make_volume_desc(dims, {-1, -0.8f, -0.9f}, {1, 0.8f, 0.9f}, 0.0f, 1.0f), {}};
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  for (uint32_t k = 0; k < dims.z; ++k)
    for (uint32_t j = 0; j < dims.y; ++j)
      for (uint32_t i = 0; i < dims.x; ++i) {
        const double dx = i - 13.0, dy = j - 11.0, dz = k - 12.0;
        const double r2 = (dx * dx + dy * dy + dz * dz) / 60.0;
        vol.values.push_back(u01(rng) < fill * std::exp(-r2) ? u01(rng) : 0.0);
      }
  return vol;
}

// A smooth 20 x 24 x 16 volume, a 128-entry transfer function and a 40 x 30 view of it at a
// step of 0.02: the case the cross-backend comparisons render.
struct SmoothCase {
  Volume vol;
  std::vector<Vec4d> tf;
  RaymarchParams rp;
};
inline SmoothCase smooth_case() {
  const UVec3 dims{20, 24, 16};
  SmoothCase c{{make_volume_desc(dims, {-1, -1.2f, -0.8f}, {1, 1.2f, 0.8f}, -0.2f, 1.1f), {}}};
  for (uint32_t k = 0; k < dims.z; ++k)
    for (uint32_t j = 0; j < dims.y; ++j)
      for (uint32_t i = 0; i < dims.x; ++i)
        c.vol.values.push_back(std::sin(0.4 * i) * std::cos(0.3 * j) + 0.05 * k);
  c.tf.resize(128);
  for (uint32_t k = 0; k < 128; ++k) {
    const double v = k / 127.0;
    c.tf[k] = {v, 1 - std::abs(2 * v - 1), 1 - v, 0.3 * v};
  }
  RaymarchParams& rp = c.rp;
  rp.volume = c.vol.desc;
  rp.width = 40;
  rp.height = 30;
  rp.eye = {2.5f, -1.5f, 2.0f};
  rp.step = 0.02f;
  rp.reference_step = 0.02f;
  rp.tf_size = 128;
  return c;
}

}  // namespace masav::test
