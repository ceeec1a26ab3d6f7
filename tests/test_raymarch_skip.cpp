// The raymarch's skip arithmetic on every backend: the next segment after an empty cell (a
// multiplication and a truncation in place of a division and a ceiling) against its definition,
// and skipping with bricks whose index is a shift (4 voxels) or an integer division (3, 5) giving
// the image of the march without skipping on a sparse volume.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "engine/kernels/atom_checks.h"
#include "engine/kernels/volume_math.h"
#include "tests/backend_fixture.h"
#include "tests/raymarch_render.h"

using namespace masav;

namespace {

// The definition: the first k >= i + 1 whose midpoint tn + (k + 1/2) step lies at or beyond t,
// n if none does; in double, from the same float inputs.
uint32_t first_segment_by_definition(float t, float tn, float step, uint32_t i, uint32_t n) {
  for (uint32_t k = i + 1u; k < n; ++k)
    if (double(tn) + (k + 0.5) * double(step) >= double(t)) return k;
  return n;
}

}  // namespace

TEST_CASE("raymarch: the segment after a skip is the first whose midpoint is past the exit") {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u01(0.0f, 1.0f);
  int checked = 0, off = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const float step = 0.01f + u01(rng);
    const float tn = 4.0f * u01(rng) - 2.0f;
    const uint32_t n = 1u + uint32_t(200.0f * u01(rng));
    const uint32_t i = uint32_t(float(n) * u01(rng)) % n;
    const float t = tn + step * (float(n) + 2.0f) * u01(rng);
    const uint32_t got = volume::first_segment_after(t, tn, 1.0f / step, i, n);
    const uint32_t want = first_segment_by_definition(t, tn, step, i, n);
    CHECK(got >= i + 1u);
    CHECK(got <= n);
    // Where a midpoint lies within float rounding of t the two may pick either side of it.
    if (got != want) {
      ++off;
      const uint32_t k = got < want ? got : want;
      CHECK(std::abs(double(tn) + (k + 0.5) * double(step) - double(t)) < 1e-5 * (1.0 + n * step));
    }
    ++checked;
  }
  CHECK(checked == 20000);
  CHECK(off < 20);
  // Exactly on a midpoint, and past the last segment.
  CHECK(volume::first_segment_after(0.0f + 3.5f * 0.25f, 0.0f, 4.0f, 0u, 10u) == 3u);
  CHECK(volume::first_segment_after(100.0f, 0.0f, 4.0f, 0u, 10u) == 10u);
  CHECK(volume::first_segment_after(-1.0f, 0.0f, 4.0f, 5u, 10u) == 6u);
}

TEST_CASE("raymarch: skipping with bricks of 3, 4 and 5 voxels keeps the image") {
  const test::Volume vol = test::sparse_cloud(0.25);
  std::vector<Vec4d> tf(64);
  for (uint32_t k = 0; k < 64; ++k) {
    const double v = k / 63.0;
    tf[k] = {v, 1 - v, 0.5, 0.4 * v};
  }
  RaymarchParams rp;
  rp.volume = vol.desc;
  rp.width = 28;
  rp.height = 20;
  rp.eye = {2.1f, -1.7f, 1.3f};
  rp.reference_step = 0.05f;
  rp.tf_size = 64;
  rp.termination_alpha = 1.0f;
  for (uint32_t brick : {3u, 4u, 5u})
    for (bool pre : {false, true})
      for (float step : {0.0371f, 0.0742f}) {  // 1/2 and 1 voxel
        CAPTURE(brick);
        CAPTURE(pre);
        CAPTURE(step);
        rp.brick = brick;
        rp.preintegrate = pre;
        rp.step = step;
        rp.skip_empty = false;
        const auto full = test::render(test::backend(), rp, vol, tf);
        rp.skip_empty = true;
        const auto skipped = test::render(test::backend(), rp, vol, tf);
        double diff = 0, alpha = 0;
        for (size_t i = 0; i < full.size(); ++i) {
          diff = std::max({diff, std::abs(full[i].x - skipped[i].x),
                           std::abs(full[i].y - skipped[i].y), std::abs(full[i].w - skipped[i].w)});
          alpha = std::max(alpha, full[i].w);
        }
        CHECK(alpha > 0.2);  // the cloud is in view
        CHECK(diff < 1e-6);
      }
}
