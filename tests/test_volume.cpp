// voxelize, volume_bricks, volume_brick_skip and raymarch on every backend: exact counts and the
// thesis's p(i), g(i), sample; brick ranges and strides; the composited opacity against the
// analytic line integral of a known volume, with the error falling as the step shrinks; empty-space
// skipping and early ray termination leave the image unchanged; the thesis's lerp mode; the CPU
// reference; bad input.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "engine/core/error.h"
#include "engine/kernels/atom_checks.h"
#include "engine/kernels/grid_cell.h"
#include "engine/util/error_metrics.h"
#include "engine/volume/preintegration.h"
#include "engine/volume/ray_integral.h"
#include "tests/backend_fixture.h"
#include "tests/raymarch_render.h"

using namespace masav;

namespace {

struct Voxels {
  std::vector<double> p, g, sample;
};

Voxels voxelize_on(Backend& b, const VoxelizeParams& vp, const std::vector<Vec4f>& pts,
                   const std::vector<double>& light) {
  auto pos = b.create<Real4>(pts.size(), "positions");
  b.upload(pos, pts);
  auto lit = b.create<Real>(light.size(), "light");
  b.upload(lit, light);
  const size_t cells = grid_cell_count(vp.grid);
  auto p = b.create<Real>(cells, "p"), g = b.create<Real>(cells, "g"),
       s = b.create<Real>(cells, "s");
  b.voxelize(vp, pos, lit, p, g, s);
  return {b.download(p), b.download(g), b.download(s)};
}

using test::Volume;

// v = a . (voxel coordinates) + d: trilinear interpolation reproduces it exactly between the
// outermost voxel centres (and clamps beyond them).
Volume ramp_volume(UVec3 dims, Vec3f lo, Vec3f hi) {
  Volume v{make_volume_desc(dims, lo, hi, 0.0f, 1.0f), {}};
  const double total = double(dims.x - 1) + (dims.y - 1) + (dims.z - 1);
  for (uint32_t k = 0; k < dims.z; ++k)
    for (uint32_t j = 0; j < dims.y; ++j)
      for (uint32_t i = 0; i < dims.x; ++i) v.values.push_back((i + j + k) / total);
  return v;
}

// Transfer function with colour 1 and alpha such that the extinction is c * v per unit length:
// alpha(v) = 1 - exp(-c v ref). With the opacity correction the composited alpha is then the
// midpoint rule for 1 - exp(-c int v ds).
std::vector<Vec4d> absorption_tf(uint32_t size, double c, double ref) {
  std::vector<Vec4d> tf(size);
  for (uint32_t k = 0; k < size; ++k) {
    const double v = double(k) / (size - 1);
    tf[k] = {1, 1, 1, 1 - std::exp(-c * v * ref)};
  }
  return tf;
}

using test::render;
using test::smooth_case;
using test::SmoothCase;

// kappa(v) = c v per unit length: absorption_tf's extinction.
struct LinearExtinction {
  double c;
  double operator()(double v) const { return c * v; }
  double antiderivative(double v) const { return 0.5 * c * v * v; }
};

// A transfer function of colour 1 whose alpha over a reference step ref has extinction e(v).
template <class Extinction>
std::vector<Vec4d> extinction_tf(uint32_t size, const Extinction& e, double ref) {
  std::vector<Vec4d> tf(size);
  for (uint32_t k = 0; k < size; ++k)
    tf[k] = {1, 1, 1, 1 - std::exp(-e(double(k) / (size - 1)) * ref)};
  return tf;
}

// The analytic opacity 1 - exp(-int kappa(v) ds) of the cubic ramp_volume(dims) on [-1, 1]^3
// seen through rp.
template <class Extinction>
std::vector<double> analytic_alpha(const RaymarchParams& rp, uint32_t dims, const Extinction& e) {
  const RaymarchLayout cam = raymarch_layout(rp);
  const double spacing = 2.0 / dims;
  std::vector<double> want(size_t(rp.width) * rp.height, 0.0);
  for (uint32_t y = 0; y < rp.height; ++y)
    for (uint32_t x = 0; x < rp.width; ++x) {
      const hd::V3<double> eye = volume::v3<double>(cam.eye);
      const hd::V3<double> d = volume::pixel_direction<double>(cam, x, y);
      double t0 = 0, t1 = 1e30;
      if (!volume::slab(eye, d, hd::V3<double>{-1, -1, -1}, hd::V3<double>{1, 1, 1}, t0, t1))
        continue;
      double o[3], du[3];
      for (int a = 0; a < 3; ++a) {
        o[a] = (hd::comp(eye, a) + 1) / spacing - 0.5;
        du[a] = hd::comp(d, a) / spacing;
      }
      const double depth =
          volume::clamped_ramp_depth(o, du, 0, dims - 1, 1.0 / (3.0 * (dims - 1)), t0, t1, e);
      want[y * rp.width + x] = 1 - std::exp(-depth);
    }
  return want;
}

}  // namespace

TEST_CASE("voxelize: exact counts, sum p = 1, g the mean light, sample = s g + t p / max p") {
  std::mt19937_64 rng(4);
  std::normal_distribution<float> gauss(0.0f, 1.3f);
  const uint32_t n = 50000;
  std::vector<Vec4f> pts(n);
  std::vector<double> light(n);
  for (uint32_t i = 0; i < n; ++i) {
    pts[i] = {gauss(rng), gauss(rng), gauss(rng), 0.0f};  // some outside the box: clamped
    light[i] = std::exp(-double(pts[i].x * pts[i].x)) * 2.0;
  }
  VoxelizeParams vp;
  vp.grid = make_grid_params({-3, -3, -3}, 0.25f, {24, 24, 24}, n);
  vp.light_to_unit = 0.8f;
  const Voxels got = voxelize_on(test::backend(), vp, pts, light);
  // Brute force in double.
  const size_t cells = grid_cell_count(vp.grid);
  std::vector<double> count(cells, 0), sum(cells, 0);
  const float origin[3] = {-3, -3, -3};
  const uint32_t dims[3] = {24, 24, 24};
  for (uint32_t i = 0; i < n; ++i) {
    const auto c = grid::point_cell(pts[i].x, pts[i].y, pts[i].z, origin, vp.grid.inv_cell, dims);
    const uint32_t id = grid::cell_id(c.x, c.y, c.z, 24, 24);
    count[id] += 1;
    sum[id] += std::min(1.0, light[i] * double(vp.light_to_unit));
  }
  const double max_count = *std::max_element(count.begin(), count.end());
  double total = 0;
  size_t count_mismatch = 0;
  for (size_t o = 0; o < cells; ++o) {  // outputs x fastest, grid cell ids z fastest
    const size_t c = (o % 24 * 24 + o / 24 % 24) * 24 + o / 576;
    count_mismatch += std::llround(got.p[o] * n) != std::llround(count[c]);
    total += got.p[o];
    const double g = count[c] ? sum[c] / count[c] : 0.0;
    CHECK(std::abs(got.g[o] - g) <= 2e-6);
    CHECK(std::abs(got.sample[o] - (vp.s * g + vp.t * count[c] / max_count)) <= 3e-6);
  }
  CHECK(count_mismatch == 0);
  CHECK(total == doctest::Approx(1.0).epsilon(1e-5));
  const Voxels ref = voxelize_on(test::reference(), vp, pts, light);
  const ErrorStats e = compare(got.sample, ref.sample, 1e-3);
  CAPTURE(describe(e));
  CHECK(e.max_abs < 3e-6);
}

TEST_CASE(
    "volume_bricks: value range over each brick and its apron, largest alpha over it, stride 1") {
  const Volume vol = ramp_volume({19, 10, 7}, {0, 0, 0}, {1.9f, 1.0f, 0.7f});
  std::vector<Vec4d> tf(16);
  for (uint32_t k = 0; k < 16; ++k) tf[k] = {0, 0, 0, k < 6 ? 0.0 : k / 16.0};
  const VolumeBrickParams bp{vol.desc, 4, 16};
  Backend& b = test::backend();
  auto v = b.create<Real>(vol.values.size(), "volume");
  b.upload(v, vol.values);
  auto t = b.create<Real4>(16, "tf");
  b.upload(t, tf);
  const UVec3 nb = brick_dims(vol.desc, 4);
  CHECK(nb.x == 5);
  CHECK(nb.z == 2);
  auto bricks = b.create<Real4>(size_t(nb.x) * nb.y * nb.z, "bricks");
  b.volume_bricks(bp, v, t, bricks);
  const auto got = b.download(bricks);
  const double total = 18 + 9 + 6;
  for (uint32_t z = 0; z < nb.z; ++z)
    for (uint32_t y = 0; y < nb.y; ++y)
      for (uint32_t x = 0; x < nb.x; ++x) {
        const auto& br = got[(z * nb.y + y) * nb.x + x];
        const double lo = (4.0 * (x + y + z)) / total;
        const double hi =
            (std::min(4 * x + 4, 18u) + std::min(4 * y + 4, 9u) + std::min(4 * z + 4, 6u)) / total;
        CHECK(br.x == doctest::Approx(lo).epsilon(1e-6));
        CHECK(br.y == doctest::Approx(hi).epsilon(1e-6));
        auto largest_alpha = [&](double from, double to) {
          double amax = 0;
          for (uint32_t k = uint32_t(from * 15); k <= std::min(15u, uint32_t(std::ceil(to * 15)));
               ++k)
            amax = std::max(amax, tf[k].w);
          return amax;
        };
        CHECK(br.z == doctest::Approx(largest_alpha(lo, hi)).epsilon(1e-6));
        CHECK(br.w == 1);  // the brick alone, until volume_brick_skip widens it
      }
}

namespace {

// Per brick, the Chebyshev distance to the nearest brick of the other kind (alpha > 0 or not),
// radius + 1 where there is none within radius: by looking at every brick.
std::vector<uint32_t> brute_strides(const std::vector<Vec4d>& bricks, UVec3 nb, uint32_t radius) {
  std::vector<uint32_t> out;
  const int n[3] = {int(nb.x), int(nb.y), int(nb.z)};
  auto occupied = [&](int x, int y, int z) {
    return bricks[(size_t(z) * n[1] + y) * n[0] + x].z > 0;
  };
  for (int z = 0; z < n[2]; ++z)
    for (int y = 0; y < n[1]; ++y)
      for (int x = 0; x < n[0]; ++x) {
        int best = int(radius) + 1;
        for (int k = 0; k < n[2]; ++k)
          for (int j = 0; j < n[1]; ++j)
            for (int i = 0; i < n[0]; ++i)
              if (occupied(i, j, k) != occupied(x, y, z))
                best =
                    std::min(best, std::max({std::abs(i - x), std::abs(j - y), std::abs(k - z)}));
        out.push_back(uint32_t(best));
      }
  return out;
}

}  // namespace

TEST_CASE(
    "volume_brick_skip: each brick's stride is the Chebyshev distance to the nearest brick of "
    "the other kind, capped at radius + 1, bit for bit against looking at every brick") {
  Backend& b = test::backend();
  const UVec3 nb{13, 9, 7};
  const size_t n = size_t(nb.x) * nb.y * nb.z;
  std::mt19937 rng(7);
  // A ball of occupied bricks, a slab, scattered single ones; and all empty, all occupied.
  std::vector<Vec4d> mixed(n), empty(n, Vec4d{0, 1, 0, 1}), full(n, Vec4d{0, 1, 0.25, 1});
  for (size_t i = 0; i < n; ++i) {
    const int x = int(i % nb.x), y = int(i / nb.x % nb.y), z = int(i / (nb.x * nb.y));
    const bool ball = (x - 4) * (x - 4) + (y - 3) * (y - 3) + (z - 3) * (z - 3) < 7;
    const bool on = ball || x == 11 || rng() % 17 == 0;
    mixed[i] = {0.125 * z, 0.25 + 0.125 * y, on ? 0.5 : 0.0, 1};  // exact in fp32
  }
  for (const auto* pattern : {&mixed, &empty, &full})
    for (uint32_t radius : {1u, 2u, 3u, 6u, 255u}) {
      CAPTURE(radius);
      auto bricks = b.create<Real4>(n, "bricks");
      b.upload(bricks, *pattern);
      auto distances = b.create<uint32_t>(2 * n, "distances");
      BrickSkipParams p;
      p.bricks = nb;
      p.radius = radius;
      for (p.axis = 0; p.axis < 3; ++p.axis) b.volume_brick_skip(p, bricks, distances);
      const auto got = b.download(bricks);
      const std::vector<uint32_t> want = brute_strides(*pattern, nb, radius);
      size_t wrong = 0, wider = 0;
      for (size_t i = 0; i < n; ++i) {
        wrong += got[i].w != double(want[i]);
        wider += want[i] > 1;
        // The other three words are left as they were.
        CHECK(got[i].x == (*pattern)[i].x);
        CHECK(got[i].y == (*pattern)[i].y);
        CHECK(got[i].z == (*pattern)[i].z);
      }
      CHECK(wrong == 0);
      if (pattern == &mixed && radius > 1) CHECK(wider > n / 8);  // the case tests something
    }
  // Bad input names the field and the allowed range.
  auto bricks = b.create<Real4>(n, "bricks");
  auto distances = b.create<uint32_t>(2 * n, "distances");
  BrickSkipParams p;
  p.bricks = nb;
  auto refused = [&](const BrickSkipParams& q, const char* what) {
    CAPTURE(what);
    CHECK_THROWS_WITH_AS(b.volume_brick_skip(q, bricks, distances), doctest::Contains(what), Error);
  };
  BrickSkipParams q = p;
  q.axis = 3;
  refused(q, "axis");
  q = p;
  q.radius = 0;
  refused(q, "radius");
  q.radius = kBrickSkipMaxRadius + 1;
  refused(q, "radius");
  q = p;
  q.bricks.y = 0;
  refused(q, "bricks.y");
  q = p;
  q.bricks.x = 14;
  refused(q, "bricks");
  auto short_distances = b.create<uint32_t>(n, "distances");
  CHECK_THROWS_WITH_AS(b.volume_brick_skip(p, bricks, short_distances),
                       doctest::Contains("distances"), Error);
}

namespace {

// The small oblique view of a ramp volume the analytic line-integral tests render: no early
// termination, a 4096-entry transfer function.
RaymarchParams analytic_view(const Volume& vol, double reference_step) {
  RaymarchParams rp;
  rp.volume = vol.desc;
  rp.width = 12;
  rp.height = 10;
  rp.eye = {2.2f, 1.7f, 2.9f};
  rp.fov_y_deg = 45;
  rp.reference_step = float(reference_step);
  rp.termination_alpha = 1.0f;
  rp.tf_size = 4096;
  return rp;
}

}  // namespace

TEST_CASE("raymarch: opacity equals the analytic line integral; error falls with the step") {
  const Volume vol = ramp_volume({24, 24, 24}, {-1, -1, -1}, {1, 1, 1});
  const double c = 1.5, ref = 0.01;
  const auto tf = absorption_tf(4096, c, ref);
  RaymarchParams rp = analytic_view(vol, ref);
  rp.skip_empty = false;
  const std::vector<double> want = analytic_alpha(rp, 24, LinearExtinction{c});
  double prev = 0;
  for (float step : {0.2f, 0.1f, 0.05f, 0.025f}) {
    rp.step = step;
    const auto img = render(test::backend(), rp, vol, tf);
    double err = 0;
    for (size_t i = 0; i < img.size(); ++i) {
      err = std::max(err, std::abs(img[i].w - want[i]));
      CHECK(std::abs(img[i].x - img[i].w) < 1e-5);  // colour 1: premultiplied colour = alpha
    }
    MESSAGE("raymarch step " << step << ": max |alpha - analytic| " << err);
    if (prev > 1e-5) CHECK(err < 0.6 * prev);
    prev = err;
  }
  CHECK(prev < 2e-4);
}

TEST_CASE(
    "raymarch pre-integrated: the analytic line integral at steps up to 5 voxels, a narrow "
    "peak in the transfer function included") {
  // Pre-integration takes the scalar as linear between samples (exact here but at the kinks
  // where an axis clamps, half a voxel inside the box: there, like the trapezoid rule, up to
  // twice the midpoint rule's error) and integrates the transfer function over that exactly: a
  // peak the midpoint rule steps over costs it nothing. The kinks set both methods' largest
  // error at fine steps.
  const Volume vol = ramp_volume({24, 24, 24}, {-1, -1, -1}, {1, 1, 1});
  const double ref = 0.01;
  RaymarchParams rp = analytic_view(vol, ref);
  auto sweep = [&](const std::vector<Vec4d>& tf, const std::vector<double>& want, bool peaked) {
    for (bool skip : {false, true})
      for (float step : {0.4f, 0.2f, 0.1f, 0.05f, 0.025f}) {
        rp.skip_empty = skip;
        rp.step = step;
        rp.preintegrate = false;
        const auto midpoint = render(test::backend(), rp, vol, tf);
        rp.preintegrate = true;
        const auto img = render(test::backend(), rp, vol, tf);
        double err = 0, midpoint_err = 0;
        for (size_t i = 0; i < img.size(); ++i) {
          err = std::max(err, std::abs(img[i].w - want[i]));
          midpoint_err = std::max(midpoint_err, std::abs(midpoint[i].w - want[i]));
          CHECK(std::abs(img[i].x - img[i].w) < 1e-5);  // colour 1: premultiplied colour = alpha
        }
        CAPTURE(peaked);
        CAPTURE(step);
        MESSAGE((peaked ? "peaked" : "linear")
                << " extinction, step " << step << " (" << step * 12 << " voxels): pre-integrated "
                << err << ", midpoint rule " << midpoint_err);
        if (peaked) {  // a step of a voxel or more: the midpoint rule misses the peak
          CHECK(err < 1.1 * midpoint_err);
          if (step >= 0.1f) CHECK(err < 0.15 * midpoint_err);
        } else {
          CHECK(err < 2.5 * midpoint_err + 1e-5);
        }
      }
  };
  const LinearExtinction linear{1.5};
  sweep(extinction_tf(4096, linear, ref), analytic_alpha(rp, 24, linear), false);
  const volume::PeakedExtinction peak;
  sweep(extinction_tf(4096, peak, ref), analytic_alpha(rp, 24, peak), true);
}

TEST_CASE(
    "preintegrate_transfer: depth and emission per entry, their integrals as float and remainder") {
  // Colour 0.5 -> 1 -> 1 with alpha 0 -> 1 - e^-2 -> 1 (transmittance capped at kMinTransmittance).
  const std::vector<Vec4d> tf = {{0.5, 0, 0, 0}, {1, 0, 0, 1 - std::exp(-2.0)}, {1, 0, 0, 1}};
  const auto t = volume::preintegrate_transfer(tf);
  REQUIRE(t.size() == kPreintegratedPerEntry * 3);
  const double cap = -std::log(volume::kMinTransmittance);
  CHECK(t[0].w == 0);
  CHECK(t[3].w == doctest::Approx(2.0).epsilon(1e-12));
  CHECK(t[3].x == doctest::Approx(2.0).epsilon(1e-12));  // emission = colour * depth
  CHECK(t[3].y == 0);
  CHECK(t[6].w == doctest::Approx(cap).epsilon(1e-12));
  // The integrals: 0 at entry 0, then the trapezoids; float part plus remainder.
  CHECK(t[1].w == 0);
  const double sum1 = t[4].w + t[5].w, sum2 = t[7].w + t[8].w;
  CAPTURE(sum1);
  CAPTURE(sum2);
  CHECK(std::abs(sum1 - 1.0) <= 1e-15);
  CHECK(std::abs(sum2 - (1.0 + 0.5 * (2.0 + cap))) <= 1e-14);
  CHECK(double(float(t[7].w)) == t[7].w);
  CHECK(t[8].w != 0);  // 1 + (2 + 13.8) / 2 is not a float
  CHECK(std::abs(t[8].w) <= 1e-7 * t[7].w);
  CHECK_THROWS_WITH_AS(volume::preintegrate_transfer({{1, 1, 1, 1}}),
                       doctest::Contains("at least 2 entries"), Error);
}

TEST_CASE("raymarch: skipping empty bricks and early termination keep the image") {
  // A blob in one corner of an otherwise empty volume; the transfer function is 0 below 0.2.
  const UVec3 dims{32, 32, 32};
  Volume vol{make_volume_desc(dims, {0, 0, 0}, {1, 1, 1}, 0.0f, 1.0f), {}};
  for (uint32_t k = 0; k < dims.z; ++k)
    for (uint32_t j = 0; j < dims.y; ++j)
      for (uint32_t i = 0; i < dims.x; ++i) {
        const double dx = i - 22.0, dy = j - 12.0, dz = k - 18.0;
        vol.values.push_back(std::exp(-(dx * dx + dy * dy + dz * dz) / 30.0));
      }
  std::vector<Vec4d> tf(64);
  for (uint32_t k = 0; k < 64; ++k) {
    const double v = k / 63.0;
    tf[k] = {v, 1 - v, 0.5, v < 0.2 ? 0.0 : 0.6 * (v - 0.2)};
  }
  RaymarchParams rp;
  rp.volume = vol.desc;
  rp.width = rp.height = 24;
  rp.eye = {1.8f, 1.3f, -1.2f};
  rp.target = {0.5f, 0.5f, 0.5f};
  rp.step = 0.004f;
  rp.reference_step = 0.01f;
  rp.tf_size = 64;
  for (bool pre : {false, true})
    for (float step : {0.004f, 0.03f}) {  // the second, 1 voxel: segments cross bricks often
      CAPTURE(pre);
      CAPTURE(step);
      rp.preintegrate = pre;
      rp.step = step;
      rp.termination_alpha = 1.0f;
      rp.skip_empty = false;
      const auto full = render(test::backend(), rp, vol, tf);
      rp.skip_empty = true;
      const auto skipped = render(test::backend(), rp, vol, tf);
      double diff = 0, alpha = 0;
      for (size_t i = 0; i < full.size(); ++i) {
        diff = std::max(
            {diff, std::abs(full[i].x - skipped[i].x), std::abs(full[i].w - skipped[i].w)});
        alpha = std::max(alpha, full[i].w);
      }
      CHECK(alpha > 0.5);  // the blob is in view
      CHECK(diff < 1e-6);
      rp.termination_alpha = 0.9f;
      const auto ert = render(test::backend(), rp, vol, tf);
      for (size_t i = 0; i < full.size(); ++i) {
        // Stopping at alpha >= 0.9 loses at most the remaining 1 - alpha of the colour.
        CHECK(std::abs(ert[i].x - full[i].x) <= 1 - std::min(ert[i].w, 1.0) + 1e-6);
        if (full[i].w >= 0.9) CHECK(ert[i].w >= 0.9);
      }
    }
}

// A backend may keep what it derives from a volume between frames (Vulkan on a CPU device: its
// voxels four to a texel, compute/vk_volume.cpp); a volume rewritten in place, by an upload or
// by a command, must then render as a fresh one does.
TEST_CASE("raymarch: a volume rewritten between frames renders as a fresh volume") {
  Backend& b = test::backend();
  auto same = [](const std::vector<Vec4d>& x, const std::vector<Vec4d>& y) {
    if (x.size() != y.size()) return false;
    for (size_t i = 0; i < x.size(); ++i)
      if (x[i].x != y[i].x || x[i].y != y[i].y || x[i].z != y[i].z || x[i].w != y[i].w)
        return false;
    return true;
  };
  SmoothCase c = smooth_case();
  const Volume first = c.vol;
  Volume second = c.vol, third = c.vol;
  for (size_t i = 0; i < c.vol.values.size(); ++i) {
    second.values[i] = 0.9 - 0.8 * c.vol.values[i];
    third.values[i] = 0.5 * c.vol.values[i] + 0.3 * std::cos(0.7 * double(i));
  }
  auto v = b.create<Real>(first.values.size(), "volume");
  auto t = b.create<Real4>(c.tf.size(), "tf");
  b.upload(t, c.tf);
  const UVec3 nb = brick_dims(c.rp.volume, c.rp.brick);
  auto bricks = b.create<Real4>(size_t(nb.x) * nb.y * nb.z, "bricks");
  auto img = b.create<Real4>(size_t(c.rp.width) * c.rp.height, "image");
  auto frame = [&] {
    volume::fill_bricks(b, {c.rp.volume, c.rp.brick, c.rp.tf_size}, v, t, bricks);
    b.raymarch(c.rp, v, t, bricks, img, nullptr);
    return b.download(img);
  };
  b.upload(v, first.values);
  CHECK(same(frame(), render(b, c.rp, first, c.tf)));
  b.upload(v, second.values);  // the same buffer, new contents from the host
  const auto from_upload = frame();
  CHECK(same(from_upload, render(b, c.rp, second, c.tf)));
  CHECK(!same(from_upload, render(b, c.rp, first, c.tf)));
  auto other = b.create<Real>(third.values.size(), "other volume");
  b.upload(other, third.values);
  b.copy(other, v);  // new contents from a command
  CHECK(same(frame(), render(b, c.rp, third, c.tf)));
}

TEST_CASE("raymarch: the thesis's lerp compositing of n samples of a uniform volume") {
  Volume vol{make_volume_desc({8, 8, 8}, {-1, -1, -1}, {1, 1, 1}, 0.0f, 1.0f),
             std::vector<double>(512, 0.5)};
  std::vector<Vec4d> tf = {{0.2, 0.4, 0.6, 0.1}, {0.2, 0.4, 0.6, 0.1}};
  RaymarchParams rp;
  rp.volume = vol.desc;
  rp.width = rp.height = 3;
  rp.eye = {0, 0, 5};
  rp.step = 0.1f;
  rp.tf_size = 2;
  rp.mode = Compositing::lerp;
  const auto img = render(test::backend(), rp, vol, tf);
  // The centre ray crosses 2.0 of the box: n = 20 samples, each blending in alpha 0.1.
  const double a = 1 - std::pow(0.9, 20);
  CHECK(img[4].w == doctest::Approx(a).epsilon(1e-5));
  CHECK(img[4].x == doctest::Approx(0.2 * a).epsilon(1e-5));
  CHECK(img[4].z == doctest::Approx(0.6 * a).epsilon(1e-5));
}

TEST_CASE("raymarch matches the CPU reference on a smooth volume with the default colours") {
  SmoothCase sc = smooth_case();
  const Volume& vol = sc.vol;
  const std::vector<Vec4d>& tf = sc.tf;
  RaymarchParams& rp = sc.rp;
  for (int variant : {0, 1, 2}) {  // front to back, lerp, front to back pre-integrated
    const Compositing mode = variant == 1 ? Compositing::lerp : Compositing::front_to_back;
    rp.mode = mode;
    rp.preintegrate = variant == 2;
    const auto got = render(test::backend(), rp, vol, tf),
               want = render(test::reference(), rp, vol, tf);
    double err = 0;
    for (size_t i = 0; i < got.size(); ++i)
      err = std::max({err, std::abs(got[i].x - want[i].x), std::abs(got[i].y - want[i].y),
                      std::abs(got[i].z - want[i].z), std::abs(got[i].w - want[i].w)});
    CAPTURE(variant);
    CHECK(err < 1e-4);
  }
}

TEST_CASE("voxelize and raymarch reject bad input, naming the field") {
  Backend& b = test::backend();
  Volume vol{make_volume_desc({8, 8, 8}, {0, 0, 0}, {1, 1, 1}, 0.0f, 1.0f),
             std::vector<double>(512, 0.5)};
  RaymarchParams rp;
  rp.volume = vol.desc;
  rp.width = rp.height = 4;
  rp.tf_size = 2;
  auto v = b.create<Real>(512, "volume");
  auto t = b.create<Real4>(2, "tf");
  auto bricks = b.create<Real4>(1, "bricks");
  auto img = b.create<Real4>(16, "image");
  rp.step = 1e-6f;
  CHECK_THROWS_WITH_AS(b.raymarch(rp, v, t, bricks, img, nullptr),
                       doctest::Contains("invalid step"), Error);
  rp.step = 0.01f;
  rp.tf_size = 1;
  CHECK_THROWS_WITH_AS(b.raymarch(rp, v, t, bricks, img, nullptr), doctest::Contains("tf_size"),
                       Error);
  rp.tf_size = 2;
  rp.up = {0, 0, 1};  // parallel to the view direction (eye on +z looking at the origin)
  CHECK_THROWS_WITH_AS(b.raymarch(rp, v, t, bricks, img, nullptr), doctest::Contains("invalid up"),
                       Error);
  rp.up = {0, 1, 0};
  rp.volume.dims = {8, 8, 9};
  CHECK_THROWS_WITH_AS(b.raymarch(rp, v, t, bricks, img, nullptr), doctest::Contains("volume size"),
                       Error);
  rp.volume.value_max = rp.volume.value_min;
  CHECK_THROWS_WITH_AS(b.raymarch(rp, v, t, bricks, img, nullptr), doctest::Contains("value range"),
                       Error);
  rp.volume = vol.desc;
  rp.preintegrate = true;
  CHECK_THROWS_WITH_AS(b.raymarch(rp, v, t, bricks, img, nullptr),
                       doctest::Contains("invalid tf_integral = none"), Error);
  auto table = b.create<Real4>(kPreintegratedPerEntry * 2 - 1, "table");
  CHECK_THROWS_WITH_AS(b.raymarch(rp, v, t, bricks, img, &table), doctest::Contains("tf_integral"),
                       Error);
  table = b.create<Real4>(kPreintegratedPerEntry * 2, "table");
  rp.mode = Compositing::lerp;
  CHECK_THROWS_WITH_AS(b.raymarch(rp, v, t, bricks, img, &table),
                       doctest::Contains("invalid preintegrate = on with lerp"), Error);
  rp.mode = Compositing::front_to_back;
  rp.preintegrate = false;
  VoxelizeParams vp;
  vp.grid = make_grid_params({0, 0, 0}, 0.5f, {2, 2, 2}, 0);
  auto pos = b.create<Real4>(4, "pos");
  auto lit = b.create<Real>(4, "light");
  auto out = b.create<Real>(8, "out");
  CHECK_THROWS_WITH_AS(b.voxelize(vp, pos, lit, out, out, out), doctest::Contains("particles"),
                       Error);
  vp.grid.n = 4;
  vp.s = 2;
  CHECK_THROWS_WITH_AS(b.voxelize(vp, pos, lit, out, out, out), doctest::Contains("invalid s"),
                       Error);
}
