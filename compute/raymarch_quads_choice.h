#pragma once
// Whether the Vulkan raymarch reads its volume four voxels to a texel (shaders/raymarch_quads.comp,
// specialisation constant kSpecVolumeQuads of shaders/raymarch.comp). lavapipe fetches a one-float
// texel with a gather per lane and a four-float texel with contiguous loads, so two quad texels
// cost it less than eight voxels: on a CPU device, yes. A GPU's texture path serves the eight
// voxels from its cache, and the quads would only add a pass of four times the volume's bytes per
// frame. VulkanTuning::raymarch_quads overrides it.
#include <cstdint>
#include <string_view>

#include "engine/core/tuning.h"

namespace masav::vk {

// device_type as Capabilities::device_type ("cpu" for lavapipe).
bool raymarch_quads_wanted(const VulkanTuning& t, std::string_view device_type);

// The largest quad buffer raymarch makes (bytes): past it (a 161^3 volume and up) it gathers
// voxels one by one, without the extra memory.
inline constexpr uint64_t kMaxRayQuadBytes = uint64_t(64) << 20;

}  // namespace masav::vk
