#pragma once
// Which variant of a shader a dispatch runs: its specialisation constants, each set by the name
// of its meaning (the ids: shaders/spec_ids.h). The single-dispatch kernels fill one struct per
// kernel family in one place (VulkanBackend::run_kernel, vk_kernels.cpp); the backend's own
// passes name their few constants where they run them (vk_sort.cpp, vk_scatter.cpp). A pipeline
// is built once per shader and distinct set of constants (Pipelines::get).
#include <cstdint>
#include <optional>
#include <vector>

namespace masav::vk {

// One specialisation constant: its id (shaders/spec_ids.h, kSpecFirstVariant and up) and value.
struct SpecConstant {
  uint32_t id;
  uint32_t value;
  bool operator==(const SpecConstant&) const = default;
};
using SpecConstants = std::vector<SpecConstant>;

// raymarch (shaders/raymarch.comp) is specialised on the flags that choose its code paths, on the
// brick size, on the form of its opacity correction's power and on reading the volume as quads:
// lavapipe runs a branch that no lane takes, loads and all, unless the branch is compiled out,
// and divides by a brick size it does not know lane by lane.
struct RaymarchVariant {
  uint32_t modes = 0;     // bits & kRayModeFlags (engine/kernels/atom_params.h)
  uint32_t brick = 4;     // the brick's edge, in voxels
  uint32_t pow_form = 0;  // kRayPow*: volume::pow_step_form
  bool quads = false;     // the volume four voxels to a texel (compute/raymarch_quads_choice.h)
  SpecConstants constants() const;
};

// The SPH kernels (shaders/sph_density.comp, sph_forces.comp) and the DFSPH solves
// (shaders/dfsph_*.comp): a kernel sets the fields its shader reads and leaves the others empty,
// so that no pipeline is built twice for a switch its shader does not have.
struct SphVariant {
  std::optional<uint32_t> model;     // SphPressureModel (shaders/common/sph.glsl)
  std::optional<bool> coop_walk;     // rows walked by subgroup clusters (sph_coop.glsl)
  std::optional<bool> wall_split;    // the walk split at the walls (sph_walk.glsl)
  std::optional<uint32_t> reach;     // SphReach: how sph_density uses the reach masks
  std::optional<bool> images_after;  // sph_forces adds the wall images after its masked walk
  std::optional<bool> state;         // the neighbour state is bound (sph_density, sph_forces)
  SpecConstants constants() const;
};

}  // namespace masav::vk
