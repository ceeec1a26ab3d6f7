#pragma once
// Which neighbour walk the Vulkan SPH kernels take (specialisation constant 4 of
// shaders/common/sph_coop.glsl). The cooperative walk turns a SIMD CPU driver's per-lane gathers
// into contiguous loads and register permutes: on lavapipe it is the faster one. On a GPU the
// per-lane walk is (an H100, 2026-11-26, 1,048,576 particles: density 0.357 ms per lane against
// 0.878 together, the leapfrog step 0.953 against 1.479 ms), since the caches serve the lanes'
// overlapping rows and the unions only add shuffles. MASAV_VK_SPH_COOP=on|off|auto overrides it.
#include <string_view>

namespace masav::vk {

// device_type as Capabilities::device_type ("cpu" for lavapipe). Throws on a bad
// MASAV_VK_SPH_COOP.
bool sph_coop_walk(std::string_view device_type);

}  // namespace masav::vk
