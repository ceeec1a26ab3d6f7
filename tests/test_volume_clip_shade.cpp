// raymarch's clipping plane and gradient shading on every backend: clipping a uniform sphere
// keeps the analytic chord of the kept half; shading lights the side facing the light and darkens
// the limb; both off (whatever their other settings) leave the image bit-identical; both on, the
// backend matches the CPU reference at the raymarch's tolerance; the gradient's shared-cell path
// equals its six trilinear lookups; bad settings are refused.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "engine/core/error.h"
#include "engine/kernels/atom_checks.h"
#include "engine/kernels/volume_math.h"
#include "tests/backend_fixture.h"
#include "tests/raymarch_render.h"

using namespace masav;
using test::render;
using test::smooth_case;
using test::SmoothCase;
using test::Volume;

namespace {

constexpr double kRadius = 0.7;

// A sphere of radius kRadius at the centre of [-1, 1]^3 with value 1 inside and 0 outside,
// anti-aliased over one voxel: each voxel holds its centre's signed distance inside the surface
// in voxels plus 1/2, clamped to [0, 1], so the trilinear field crosses 1/2 on the sphere and its
// integral along a chord is the chord's length to well under a voxel.
Volume sphere_volume(uint32_t n) {
  Volume v{make_volume_desc({n, n, n}, {-1, -1, -1}, {1, 1, 1}, 0.0f, 1.0f), {}};
  const double h = 2.0 / n;
  for (uint32_t k = 0; k < n; ++k)
    for (uint32_t j = 0; j < n; ++j)
      for (uint32_t i = 0; i < n; ++i) {
        const double x = -1 + (i + 0.5) * h, y = -1 + (j + 0.5) * h, z = -1 + (k + 0.5) * h;
        const double r = std::sqrt(x * x + y * y + z * z);
        v.values.push_back(std::clamp((kRadius - r) / h + 0.5, 0.0, 1.0));
      }
  return v;
}

// Colour 1 and extinction c v per unit length (alpha over the reference step ref).
std::vector<Vec4d> absorbing_tf(uint32_t size, double c, double ref) {
  std::vector<Vec4d> tf(size);
  for (uint32_t k = 0; k < size; ++k) tf[k] = {1, 1, 1, 1 - std::exp(-c * ref * k / (size - 1))};
  return tf;
}

// The length of the ray o + d t (d unit) inside the sphere and on the kept side of the plane
// z = 0 (keep_below: z <= 0).
double clipped_chord(hd::V3<double> o, hd::V3<double> d, bool keep_below) {
  const double b = hd::dot(o, d), c = hd::dot(o, o) - kRadius * kRadius;
  const double disc = b * b - c;
  if (disc <= 0) return 0;
  double t0 = -b - std::sqrt(disc), t1 = -b + std::sqrt(disc);
  if (d.z != 0) {
    const double tp = -o.z / d.z;
    if ((d.z > 0) == keep_below)
      t1 = std::min(t1, tp);
    else
      t0 = std::max(t0, tp);
  } else if ((o.z <= 0) != keep_below) {
    return 0;
  }
  return std::max(0.0, t1 - t0);
}

// A camera on +z looking at the centre: with an odd image size the middle pixel's ray is the z
// axis, perpendicular to a clipping plane across z.
RaymarchParams z_view(const Volume& vol, uint32_t size) {
  RaymarchParams rp;
  rp.volume = vol.desc;
  rp.width = rp.height = size;
  rp.eye = {0, 0, 3};
  rp.fov_y_deg = 40;
  rp.step = 0.005f;
  rp.reference_step = 0.01f;
  rp.termination_alpha = 1.0f;
  rp.tf_size = 1024;
  return rp;
}

double depth(const Vec4d& px) {
  return -std::log(1 - px.w);
}

}  // namespace

TEST_CASE(
    "raymarch clip: a plane through a uniform sphere's centre halves the optical path; every "
    "ray keeps the analytic chord of the kept half") {
  const Volume vol = sphere_volume(64);
  const double c = 1.5, ref = 0.01;
  const auto tf = absorbing_tf(1024, c, ref);
  RaymarchParams rp = z_view(vol, 15);
  const uint32_t mid = 7 * 15 + 7;
  const double h = 2.0 / 64;  // the voxel
  for (bool pre : {false, true}) {
    CAPTURE(pre);
    rp.preintegrate = pre;
    rp.clip.enabled = false;
    const auto full = render(test::backend(), rp, vol, tf);
    CHECK(depth(full[mid]) == doctest::Approx(c * 2 * kRadius).epsilon(0.01));
    const RaymarchLayout cam = raymarch_layout(rp);
    for (bool keep_above : {true, false}) {
      CAPTURE(keep_above);
      rp.clip = {true, 2, 0.5f, keep_above};
      const auto half = render(test::backend(), rp, vol, tf);
      // Through the centre along z: half the path, whichever half is kept.
      CHECK(depth(half[mid]) == doctest::Approx(0.5 * depth(full[mid])).epsilon(1e-3));
      double err = 0, chords = 0;
      for (uint32_t y = 0; y < rp.height; ++y)
        for (uint32_t x = 0; x < rp.width; ++x) {
          const hd::V3<double> eye = volume::v3<double>(cam.eye);
          const hd::V3<double> d = volume::pixel_direction<double>(cam, x, y);
          // Rays that graze the surface cross its one-voxel ramp over a long way: left out.
          const hd::V3<double> closest = eye - d * hd::dot(eye, d);
          if (hd::length(closest) > kRadius - 2 * h) continue;
          const double want = c * clipped_chord(eye, d, !keep_above);
          err = std::max(err, std::abs(depth(half[y * rp.width + x]) - want));
          ++chords;
        }
      const std::string label =
          std::string(keep_above ? "clip above" : "clip below") + (pre ? ", pre-integrated" : "");
      MESSAGE(label << ": max |depth - c chord| " << err << " over " << chords << " rays");
      CHECK(chords > 40);
      CHECK(err < c * h / 2);  // within half a voxel of the chord (measured: a quarter)
    }
  }
  // The plane on the box's face towards the camera (z = 1) keeping what is below it keeps
  // everything: the same image as no plane, bit for bit (the span is cut where the box already
  // cuts it).
  rp.preintegrate = false;
  rp.clip = {false, 2, 0.5f, true};
  const auto full = render(test::backend(), rp, vol, tf);
  rp.clip = {true, 2, 1.0f, false};
  const auto kept = render(test::backend(), rp, vol, tf);
  for (size_t i = 0; i < full.size(); ++i) CHECK(kept[i].w == full[i].w);
  // Keeping what is above that face keeps nothing.
  rp.clip = {true, 2, 1.0f, true};
  for (const Vec4d& px : render(test::backend(), rp, vol, tf)) CHECK(px.w == 0);
}

TEST_CASE("raymarch shading: the side facing the light is brighter than the limb") {
  const Volume vol = sphere_volume(48);
  // Nearly opaque within a few voxels of the surface: the colour comes from where the normal is.
  const auto tf = absorbing_tf(256, 60.0, 0.01);
  RaymarchParams rp = z_view(vol, 33);
  rp.step = 0.01f;
  rp.tf_size = 256;
  rp.shading.enabled = true;
  // Colour per unit opacity along the horizontal line through the centre.
  auto row = [&](const std::vector<Vec4d>& img) {
    std::vector<double> r;
    for (uint32_t x = 0; x < rp.width; ++x) {
      const Vec4d& px = img[16 * rp.width + x];
      r.push_back(px.w > 0.5 ? px.x / px.w : -1);
    }
    return r;
  };
  for (bool pre : {false, true}) {
    CAPTURE(pre);
    rp.preintegrate = pre;
    rp.shading.headlight = true;
    const auto lit = row(render(test::backend(), rp, vol, tf));
    // The middle faces the headlight: ambient + diffuse = 1, plus the highlight.
    const double mid = lit[16];
    uint32_t limb = 0;
    while (lit[limb] < 0) ++limb;  // the outermost pixel the sphere covers
    MESSAGE(std::string(pre ? "headlight, pre-integrated" : "headlight")
            << ": centre " << mid << ", limb " << lit[limb]);
    CHECK(mid > 1.1);
    CHECK(lit[limb] < 0.75);
    CHECK(lit[limb] < lit[16 - 4]);
    // A light from +x: the +x side (right of the image) is brighter than the -x side.
    rp.shading.headlight = false;
    rp.shading.light_dir = {1, 0, 0.2f};
    const auto side = row(render(test::backend(), rp, vol, tf));
    CHECK(side[32 - limb - 2] > side[limb + 2] + 0.3);
    // Shading off: colour 1 per unit opacity everywhere, as the transfer function says.
    rp.shading.enabled = false;
    for (double v : row(render(test::backend(), rp, vol, tf)))
      if (v >= 0) CHECK(v == doctest::Approx(1.0).epsilon(1e-5));
    rp.shading.enabled = true;
  }
}

TEST_CASE("raymarch: clip and shading off leave the image bit-identical, whatever their settings") {
  const Volume vol = sphere_volume(24);
  std::vector<Vec4d> tf(64);
  for (uint32_t k = 0; k < 64; ++k) tf[k] = {k / 63.0, 0.5, 1 - k / 63.0, 0.2 * k / 63.0};
  RaymarchParams rp = z_view(vol, 20);
  rp.eye = {1.9f, 1.1f, 2.3f};
  rp.tf_size = 64;
  rp.step = 0.02f;
  for (int variant : {0, 1, 2}) {  // front to back, lerp, pre-integrated
    CAPTURE(variant);
    rp.mode = variant == 1 ? Compositing::lerp : Compositing::front_to_back;
    rp.preintegrate = variant == 2;
    rp.clip = {};
    rp.shading = {};
    const auto plain = render(test::backend(), rp, vol, tf);
    rp.clip = {false, 1, 0.25f, false};
    rp.shading.headlight = false;
    rp.shading.specular = 1;
    rp.shading.ambient = 0;
    const auto off = render(test::backend(), rp, vol, tf);
    bool same = true;
    for (size_t i = 0; i < plain.size(); ++i)
      same = same && plain[i].x == off[i].x && plain[i].y == off[i].y && plain[i].z == off[i].z &&
             plain[i].w == off[i].w;
    CHECK(same);
  }
}

TEST_CASE("raymarch with clip and shading matches the CPU reference") {
  SmoothCase sc = smooth_case();
  const Volume& vol = sc.vol;
  const std::vector<Vec4d>& tf = sc.tf;
  RaymarchParams& rp = sc.rp;
  rp.clip = {true, 0, 0.4f, true};
  rp.shading.enabled = true;
  for (int variant : {0, 1, 2, 3}) {  // front to back, lerp, pre-integrated; a fixed light
    CAPTURE(variant);
    rp.mode = variant == 1 ? Compositing::lerp : Compositing::front_to_back;
    rp.preintegrate = variant == 2;
    rp.shading.headlight = variant != 3;
    rp.shading.light_dir = {-0.3f, 0.8f, 0.5f};
    rp.clip.axis = uint32_t(variant % 3);
    rp.clip.keep_above = variant != 1;
    const auto got = render(test::backend(), rp, vol, tf),
               want = render(test::reference(), rp, vol, tf);
    double err = 0, lit = 0;
    for (size_t i = 0; i < got.size(); ++i) {
      err = std::max({err, std::abs(got[i].x - want[i].x), std::abs(got[i].y - want[i].y),
                      std::abs(got[i].z - want[i].z), std::abs(got[i].w - want[i].w)});
      lit = std::max(lit, want[i].w);
    }
    CHECK(lit > 0.1);  // the clipped volume is in view
    CHECK(err < 1e-4);
  }
}

TEST_CASE("central_gradient: the shared-cell path equals six trilinear lookups") {
  // Random values (seeded) on an uneven grid; points all over it, the border included, where
  // the six lookups clamp and the shared path does not apply.
  const uint32_t dims[3] = {9, 7, 6};
  std::mt19937 rng(15);
  std::uniform_real_distribution<double> value(-1, 1), unit(0, 1);
  std::vector<double> v(size_t{dims[0]} * dims[1] * dims[2]);
  for (double& x : v) x = value(rng);
  auto at = [&](uint32_t i, uint32_t j, uint32_t k) {
    return v[(size_t(k) * dims[1] + j) * dims[0] + i];
  };
  double err = 0;
  int inner = 0;
  for (int n = 0; n < 2000; ++n) {
    const hd::V3<double> u{unit(rng) * dims[0] - 1, unit(rng) * dims[1] - 1,
                           unit(rng) * dims[2] - 1};
    const hd::V3<double> g = volume::central_gradient(u, dims, at);
    for (int a = 0; a < 3; ++a) {
      hd::V3<double> e{0, 0, 0};
      (a == 0 ? e.x : a == 1 ? e.y : e.z) = 1;
      const double want = volume::trilinear(u + e, dims, at) - volume::trilinear(u - e, dims, at);
      err = std::max(err, std::abs(hd::comp(g, a) - want));
    }
    inner += u.x >= 1 && u.x < dims[0] - 2 && u.y >= 1 && u.y < dims[1] - 2 && u.z >= 1 &&
             u.z < dims[2] - 2;
  }
  CHECK(inner > 100);  // the shared path ran
  CHECK(err < 1e-14);
}

TEST_CASE("raymarch refuses a bad clipping plane or shading, naming the field") {
  Backend& b = test::backend();
  const Volume vol{make_volume_desc({8, 8, 8}, {0, 0, 0}, {1, 1, 1}, 0.0f, 1.0f),
                   std::vector<double>(512, 0.5)};
  RaymarchParams rp;
  rp.volume = vol.desc;
  rp.width = rp.height = 4;
  rp.tf_size = 2;
  auto v = b.create<Real>(512, "volume");
  auto t = b.create<Real4>(2, "tf");
  auto bricks = b.create<Real4>(64, "bricks");
  auto img = b.create<Real4>(16, "image");
  auto refused = [&](const char* what) {
    CHECK_THROWS_WITH_AS(b.raymarch(rp, v, t, bricks, img, nullptr), doctest::Contains(what),
                         Error);
  };
  rp.clip = {true, 3, 0.5f, true};
  refused("invalid clip axis = 3");
  rp.clip = {true, 1, 1.5f, true};
  refused("invalid clip position = 1.5");
  rp.clip = {true, 1, std::nanf(""), true};
  refused("invalid clip position");
  rp.clip = {};
  rp.shading.enabled = true;
  rp.shading.ambient = -0.1f;
  refused("invalid shading ambient");
  rp.shading.ambient = 0.3f;
  rp.shading.shininess = 0.5f;
  refused("invalid shading shininess = 0.5");
  rp.shading.shininess = 24;
  rp.shading.headlight = false;
  rp.shading.light_dir = {0, 0, 0};
  refused("invalid shading light_dir");
  rp.shading.light_dir = {1, 0, 0};
  b.raymarch(rp, v, t, bricks, img, nullptr);  // a fixed light is fine
}
