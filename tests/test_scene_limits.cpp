// Scene parameters whose cost or numerics the schema alone cannot bound: the scattering table's
// rows x photons budget, and the weight threshold moved off a power of the albedo so that fp32
// (GPU) and double (CPU reference) drop a photon after the same number of scatterings.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>

#include "engine/atom/atom_schema.h"
#include "engine/atom/scatter_threshold.h"
#include "engine/core/error.h"
#include "registry/scene_catalog.h"

using namespace masav;

namespace {

// The scattering after which the kernel drops a photon (its weight below the threshold), as
// fp32 and as double multiply the weight (scatter_math.h, trace_photon).
template <class T>
uint32_t dropped_after(float albedo, float threshold, uint32_t most) {
  T w = T(1);
  for (uint32_t k = 1; k <= most; ++k) {
    w *= T(albedo);
    if (w < T(threshold)) return k;
  }
  return most + 1;
}

}  // namespace

TEST_CASE("weight threshold: fp32 and double drop photons at the same scattering, any albedo") {
  // albedo 0.01: 0.01^2 is the threshold 1e-4 itself, and the two precisions round it to
  // opposite sides: the table differed between backends (chi-square p = 1e-230).
  CHECK(dropped_after<float>(0.01f, 1e-4f, 1000) != dropped_after<double>(0.01f, 1e-4f, 1000));
  const float moved = atom::separated_weight_threshold(0.01f, 1e-4f, 1000);
  CHECK(moved < 1e-4f);
  CHECK(moved > 1e-6f);
  CHECK(dropped_after<float>(0.01f, moved, 1000) == dropped_after<double>(0.01f, moved, 1000));
  // A threshold well between two powers stays as it is (the thesis's albedo 0.6).
  CHECK(atom::separated_weight_threshold(0.6f, 1e-4f, 1000) == 1e-4f);
  CHECK(atom::separated_weight_threshold(1.0f, 1e-4f, 1000) == 1e-4f);
  // Every albedo the schema allows, in steps of 1e-4 (and the cap of scatterings at its range's
  // ends): the two precisions agree.
  int moved_count = 0;
  for (int i = 100; i <= 10000; ++i) {
    const float a = float(i) * 1e-4f;
    for (uint32_t most : {1u, 1000u, 5000u}) {
      const float t = atom::separated_weight_threshold(a, 1e-4f, most);
      moved_count += t != 1e-4f;
      CAPTURE(a);
      CAPTURE(most);
      REQUIRE(dropped_after<float>(a, t, most) == dropped_after<double>(a, t, most));
    }
  }
  CHECK(moved_count > 0);
}

TEST_CASE("scattering table: rows x photons bounded, the largest photon count named") {
  scene::ParamSet p = scene::default_params(scene::find_scene_type("atom"));
  p.set("scatter.rows", int64_t(100000));
  p.set("scatter.photons", int64_t(1) << 20);  // each legal alone: 1e11 photon paths together
  CHECK_THROWS_WITH_AS(atom::scatter_params_of(p),
                       doctest::Contains("invalid scatter.photons = 1048576 (remedy: "
                                         "scatter.photons must be at most 10737 with 100000 rows"),
                       Error);
  p.set("scatter.photons", int64_t(10737));
  CHECK(atom::scatter_params_of(p).photons_per_row == 10737u);
}
