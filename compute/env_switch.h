#pragma once
// The Vulkan backend's on|off|auto switches (MASAV_VK_SPH_COOP, MASAV_VK_RAY_QUADS): each picks
// one of two code paths whose automatic choice depends on the device.
namespace masav::vk {

// `automatic` where the variable `name` is unset, empty or "auto"; true for "on", false for
// "off". Throws, naming the variable and the allowed values, on anything else.
bool env_switch(const char* name, bool automatic);

}  // namespace masav::vk
