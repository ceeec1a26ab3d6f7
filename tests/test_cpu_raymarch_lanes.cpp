// The CPU backend's raymarch several rays at a time (engine/cpu/cpu_raymarch_lanes.h) against the
// shared body's march of one pixel in fp32 (KernelBody<raymarch>::pixel<float>, what CUDA runs):
// the same image, pixel for pixel, over views from outside and inside the box, steps whose
// opacity correction is a square root or a pow, early termination on and off, skipping on and off
// with bricks whose index is a shift or a division, clipping, gradient shading (inside the volume
// and at its faces, headlight or fixed light), and images whose size leaves lanes idle at the end.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "engine/cpu/cpu_backend.h"
#include "engine/cpu/cpu_raymarch_lanes.h"
#include "engine/kernels/atom_body.h"
#include "engine/kernels/atom_checks.h"
#include "engine/volume/brick_skip.h"
#include "engine/volume/preintegration.h"
#include "tests/raymarch_render.h"

using namespace masav;

namespace {

struct Scene {
  test::Volume vol;
  std::vector<Vec4d> tf;
};

// A sparse cloud under a transfer function that is transparent at 0: empty bricks between
// occupied ones.
Scene sparse_cloud() {
  Scene s{test::sparse_cloud(0.4), std::vector<Vec4d>(64)};
  for (uint32_t k = 0; k < 64; ++k) {
    const double v = k / 63.0;
    s.tf[k] = {v, 1 - v, 0.5, v < 0.1 ? 0.0 : 0.6 * v};
  }
  return s;
}

// The smooth field of the cross-backend comparisons, opaque enough for early termination, over a
// two-entry transfer function.
Scene smooth_field() {
  return {test::smooth_case().vol, {{0.1, 0.2, 0.9, 0.0}, {1.0, 0.6, 0.1, 0.9}}};
}

std::vector<hd::V4<float>> to_float4(const std::vector<Vec4d>& v) {
  std::vector<hd::V4<float>> out(v.size());
  for (size_t i = 0; i < v.size(); ++i)
    out[i] = {float(v[i].x), float(v[i].y), float(v[i].z), float(v[i].w)};
  return out;
}

struct Compared {
  double max_diff = 0;   // largest |lanes - shared body| over every pixel's RGBA
  double max_alpha = 0;  // the image's largest alpha (something is in view)
  size_t identical = 0, pixels = 0;
};

Compared compare(const Scene& s, const RaymarchParams& rp, cpu::RayLanes lanes) {
  cpu::CpuBackend b(2);
  auto vol = b.create<Real>(s.vol.values.size(), "volume");
  b.upload(vol, s.vol.values);
  auto tf = b.create<Real4>(s.tf.size(), "tf");
  b.upload(tf, s.tf);
  const UVec3 nb = brick_dims(rp.volume, rp.brick);
  auto bricks = b.create<Real4>(size_t(nb.x) * nb.y * nb.z, "bricks");
  volume::fill_bricks(b, {rp.volume, rp.brick, rp.tf_size}, vol, tf, bricks);
  const std::vector<hd::V4<float>> tf32 = to_float4(s.tf), bricks32 = to_float4(b.download(bricks));
  const std::vector<hd::V4<float>> integral32 = to_float4(volume::preintegrate_transfer(s.tf));
  std::vector<float> vol32(s.vol.values.begin(), s.vol.values.end());
  const UVec3 d = rp.volume.dims;
  std::vector<float> padded(size_t(d.x + 1) * (d.y + 1) * (d.z + 1));
  cpu::pad_volume(s.vol.values.data(), d, 0, d.z + 1, padded.data());

  const RaymarchLayout c = raymarch_layout(rp);
  REQUIRE(cpu::raymarch_lanes_apply(c));
  std::vector<double> image(4 * size_t(rp.width) * rp.height, -1.0);
  cpu::raymarch_lanes(c, padded.data(), tf32.data(), bricks32.data(), integral32.data(), 0,
                      volume::tiled_pixel_count(rp.width, rp.height), image.data(), lanes);
  Compared out;
  for (uint32_t y = 0; y < rp.height; ++y)
    for (uint32_t x = 0; x < rp.width; ++x) {
      const volume::V4<float> want = KernelBody<KernelId::raymarch>::pixel<float>(
          c, x, y, vol32.data(), tf32.data(), bricks32.data(), integral32.data());
      const double* got = &image[4 * (size_t(y) * rp.width + x)];
      const double w[4] = {want.r, want.g, want.b, want.a};
      bool same = true;
      for (int ch = 0; ch < 4; ++ch) {
        out.max_diff = std::max(out.max_diff, std::abs(got[ch] - w[ch]));
        same = same && got[ch] == w[ch];
      }
      out.max_alpha = std::max(out.max_alpha, w[3]);
      out.identical += same;
      ++out.pixels;
    }
  return out;
}

void check_lanes(cpu::RayLanes lanes, const char* name) {
  const Scene scenes[] = {sparse_cloud(), smooth_field()};
  size_t identical = 0, pixels = 0, cases = 0;
  double worst = 0;
  auto check = [&](const Compared& r) {
    CHECK(r.max_alpha > 0.2);  // something is in view
    CHECK(r.max_diff <= 1e-6);
    identical += r.identical;
    pixels += r.pixels;
    worst = std::max(worst, r.max_diff);
    ++cases;
  };
  for (int si = 0; si < 2; ++si) {
    const Scene& s = scenes[si];
    const float voxel = (s.vol.desc.box_max.x - s.vol.desc.box_min.x) / float(s.vol.desc.dims.x);
    const Vec3f eyes[] = {{2.1f, -1.7f, 1.3f}, {0.05f, -0.1f, 0.02f}, {0.0f, -3.0f, 0.0f}};
    for (const Vec3f& eye : eyes)
      for (float step_voxels : {0.5f, 1.0f, 0.37f})
        for (uint32_t brick : {2u, 3u})
          for (bool skip : {true, false})
            for (float termination : {0.99f, 1.0f})
              for (bool pre : {false, true}) {
                RaymarchParams rp;
                rp.volume = s.vol.desc;
                rp.width = 29;  // 4 tiles across, the last one partly outside: idle lanes
                rp.height = 19;
                rp.eye = eye;
                rp.up = {0, 0, 1};
                rp.fov_y_deg = 60.0f;
                rp.reference_step = voxel;
                rp.step = step_voxels * voxel;
                rp.tf_size = uint32_t(s.tf.size());
                rp.brick = brick;
                rp.skip_empty = skip;
                rp.termination_alpha = termination;
                rp.preintegrate = pre;
                CAPTURE(si);
                CAPTURE(eye.x);
                CAPTURE(step_voxels);
                CAPTURE(brick);
                CAPTURE(skip);
                CAPTURE(termination);
                CAPTURE(pre);
                check(compare(s, rp, lanes));
              }
  }
  // Clipping and shading (per lane, on the samples that are visible).
  for (bool shade : {false, true}) {
    const Scene s = smooth_field();
    RaymarchParams rp;
    rp.volume = s.vol.desc;
    rp.width = 23;
    rp.height = 17;
    rp.eye = {2.5f, -1.5f, 2.0f};
    rp.reference_step = 0.1f;
    rp.step = 0.05f;
    rp.tf_size = 2;
    rp.clip.enabled = true;
    rp.clip.axis = 1;
    rp.clip.position = 0.4f;
    rp.shading.enabled = shade;
    CAPTURE(shade);
    check(compare(s, rp, lanes));
  }
  // Gradient shading: lanes inside the volume (32 voxels of the cell's edges) and near its faces
  // (six trilinear lookups), the light at the camera or fixed, from outside and inside the box.
  for (int si = 0; si < 2; ++si)
    for (const Vec3f& eye : {Vec3f{2.1f, -1.7f, 1.3f}, Vec3f{0.05f, -0.1f, 0.02f}})
      for (bool headlight : {true, false})
        for (bool pre : {false, true}) {
          const Scene& s = scenes[si];
          const float voxel =
              (s.vol.desc.box_max.x - s.vol.desc.box_min.x) / float(s.vol.desc.dims.x);
          RaymarchParams rp;
          rp.volume = s.vol.desc;
          rp.width = 29;
          rp.height = 19;
          rp.eye = eye;
          rp.up = {0, 0, 1};
          rp.fov_y_deg = 60.0f;
          rp.reference_step = voxel;
          rp.step = 0.5f * voxel;
          rp.tf_size = uint32_t(s.tf.size());
          rp.shading.enabled = true;
          rp.shading.headlight = headlight;
          rp.shading.light_dir = {0.3f, -1.0f, 0.5f};
          rp.shading.specular = 0.6f;
          rp.shading.shininess = 12.0f;
          rp.preintegrate = pre;
          CAPTURE(pre);
          CAPTURE(si);
          CAPTURE(eye.x);
          CAPTURE(headlight);
          check(compare(s, rp, lanes));
        }
  std::printf(
      "raymarch lanes (%s): %zu cases, %zu of %zu pixels bit-identical, largest difference "
      "%.3g\n",
      name, cases, identical, pixels, worst);
}

}  // namespace

TEST_CASE("raymarch lanes: the CPU backend's rays in SIMD lanes give the shared body's image") {
  SUBCASE("four lanes (SSE)") {
    check_lanes(cpu::RayLanes::four, "four");
  }
  SUBCASE("eight lanes (AVX2)") {
    if (cpu::ray_lanes_avx2_available())
      check_lanes(cpu::RayLanes::best, "eight");
    else
      std::printf("note: this CPU has no AVX2: the eight-lane march is not tested here\n");
  }
}

TEST_CASE("pad_volume: one more voxel on each axis, a copy of the last") {
  const UVec3 d{3, 2, 2};
  std::vector<double> v(12);
  for (size_t i = 0; i < v.size(); ++i) v[i] = double(i) + 0.5;
  std::vector<float> p(4 * 3 * 3, -1.0f);
  cpu::pad_volume(v.data(), d, 0, 3, p.data());
  for (uint32_t k = 0; k < 3; ++k)
    for (uint32_t j = 0; j < 3; ++j)
      for (uint32_t i = 0; i < 4; ++i) {
        const size_t src = (std::min(k, 1u) * 2 + std::min(j, 1u)) * 3 + std::min(i, 2u);
        CHECK(p[(k * 3 + j) * 4 + i] == float(v[src]));
      }
}
