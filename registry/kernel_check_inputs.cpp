#include "registry/kernel_check_inputs.h"

#include <algorithm>

#include "engine/core/error.h"
#include "engine/kernels/grid_params.h"
#include "registry/scene_catalog.h"

namespace masav::verify {

KernelCheckInputs kernel_check_inputs(KernelId k, std::optional<uint32_t> points, uint64_t seed,
                                      std::string_view where) {
  KernelCheckInputs r;
  for (const auto& type : scene::scene_types()) {
    const scene::ParamSet p = scene::default_params(type);
    const auto ks = type.kernels(p);
    if (std::find(ks.begin(), ks.end(), k) != ks.end()) {
      r.scene = type.name;
      r.in = type.check_inputs(p);
      break;
    }
  }
  if (r.scene.empty()) {
    r.scene = "kernel";
    r.in.points = 5000;
    r.in.grid = make_grid_params({0, 0, 0}, 1.0f / 16, {16, 16, 16}, r.in.points);
  }
  if (points) {
    if (*points == 0) throw_invalid(where, "points", "0", "at least 1");
    r.in.points = *points;
    if (r.in.grid) r.in.grid->n = *points;
  }
  r.in.seed = seed;
  return r;
}

}  // namespace masav::verify
