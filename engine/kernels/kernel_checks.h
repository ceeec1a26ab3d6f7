#pragma once
// Validation shared by every backend, run before a kernel allocates or dispatches, so each
// backend rejects the same inputs with the same message.
#include <string_view>

#include "engine/kernels/backend.h"

namespace masav {

void check_grid(const GridParams& g, std::string_view kernel);

// The loops of a neighbour walk besides its candidates (rows, cells, walls, and the SPH kernels'
// cooperative walk: its chunk rounding, shaders/common/sph_coop.glsl): fewer than this.
inline constexpr uint32_t kWalkLoopOverhead = 535;
// The candidates an invocation that walks them `walks` times may examine within a loop budget
// of `budget` iterations: each walk's share of the budget less that overhead (at least 1).
constexpr uint32_t walk_candidates(uint32_t budget, uint32_t walks = 1) {
  const uint32_t share = budget > kWalkLoopOverhead ? (budget - kWalkLoopOverhead) / walks : 0;
  return share > 0 ? share : 1;
}
// The candidates a neighbour walk may examine on `dev`: walk_candidates of its loop budget.
uint32_t max_walk_candidates(const DeviceApi& dev);
// The SPH kernels' walks per candidate: sph_density walks its candidates, then, near a wall,
// its neighbours within h again for their wall images (shaders/sph_density.comp), as sph_forces
// may over its row masks (compute/sph_walk_choice.h), so their candidate cap is the budget's
// share of one of two walks.
inline constexpr uint32_t kSphWalks = 2;
// The most candidates an SPH kernel may examine on a device whose loop budget is `budget`.
constexpr uint32_t max_sph_candidates(uint32_t budget) {
  return walk_candidates(budget, kSphWalks);
}
// throw_invalid for a candidate cap (the field `field`) outside [1, max_walk_candidates(dev) /
// walks] (walks: the walks over the candidates one invocation may make).
void check_candidates(const DeviceApi& dev, uint32_t max_candidates, std::string_view kernel,
                      std::string_view field = "max_candidates", uint32_t walks = 1);

// Throws the error of the kernel that raised a flag of a non-zero flags word (each kDiag* flag
// belongs to one kernel: engine/kernels/grid_params.h); `detail` is the first offending index,
// `limit` what diag_limit() of its parameters gave.
void raise_diagnostics(const DeviceApi& dev, uint32_t flags, uint32_t detail, uint32_t limit);

}  // namespace masav
