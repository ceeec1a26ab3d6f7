#pragma once
// How the Vulkan SPH kernels walk their neighbours: cooperatively or per lane, and split at the
// walls or not: the automatic choice per device class of each VulkanTuning option, and why.
//
// Which neighbour walk the Vulkan SPH kernels take (specialisation constant
// kSpecSphCoopWalk, shaders/common/sph_coop.glsl). The cooperative walk turns a SIMD CPU driver's
// per-lane gathers into contiguous loads and register permutes: on lavapipe it is the faster one.
// On a GPU the per-lane walk is (an H100, 2026-11-26, 1,048,576 particles: density 0.357 ms per
// lane against 0.878 together, the leapfrog step 0.953 against 1.479 ms), since the caches serve
// the lanes' overlapping rows and the unions only add shuffles. VulkanTuning::sph_walk overrides
// it.
#include <string_view>

#include "engine/core/tuning.h"

namespace masav::vk {

// device_type as Capabilities::device_type ("cpu" for lavapipe).
bool sph_coop_walk(const VulkanTuning& t, std::string_view device_type);

// Which Vulkan SPH kernels skip the wall images in subgroups with no lane near a wall
// (specialisation constant kSpecSphWallSplit, shaders/common/sph_walk.glsl): sph_forces and the
// DFSPH solves by a second copy of their walk without the images, sph_density by skipping its loop
// over the neighbours' images after its walk. lavapipe runs every statement of a loop body in every
// pass, so there every kernel is split. A GPU skips a branch that no lane of its subgroup takes,
// but its compiler may round two copies of a walk differently, and a particle's sums must not
// depend on which particles share its subgroup (a rank's particles sit at other indices than in one
// process). sph_density's image loop adds nothing for a lane without walls, so it stays split on
// a GPU (an H200, 2026-11-27, 1,048,576 particles, with the images in its walk: 0.266 ms split
// against 0.326 in one copy). sph_forces and the DFSPH solves are not split there: unsplit,
// forces took 0.371 ms against 0.391, the solves the same.
// VulkanTuning::sph_wall_split on or off sets both.
struct SphWallSplit {
  bool density = true;
  bool others = true;  // sph_forces, dfsph_factor, dfsph_rate, dfsph_correct
};
SphWallSplit sph_wall_split(const VulkanTuning& t, std::string_view device_type);

// Whether sph_forces, over sph_density's neighbour row masks, adds the wall images in a loop of
// their own after its walk's direct terms (kSpecSphImagesAfter, shaders/sph_forces.comp),
// as sph::force_at does, rather than per neighbour inside the walk. After: each loop is written
// once, so no subgroup's copy depends on its neighbours in the subgroup (what keeps the forces
// unsplit on a GPU), a subgroup with no lane near a wall skips the images' loop, and the walk's
// loop holds none of the seven images' terms (CUDA's forces kernel on sm_90: 95 registers with
// the images inside, 64 apart). Inside: the lanes near a wall make one pass per neighbour, not
// two; on lavapipe, 32,768 particles, forces took 13.6-14.3 ms inside against 14.7-15.8 after
// (dam break) and 12.4-13.4 against 12.8-13.5 (water). auto: after on a GPU, inside on a CPU
// device (tools/gpu-report times it against inside on a GPU). VulkanTuning::sph_images_after
// overrides it.
bool sph_images_after(const VulkanTuning& t, std::string_view device_type);

}  // namespace masav::vk
