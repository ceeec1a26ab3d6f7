#include "compute/device/vk_environment.h"

#include <fmt/format.h>

#include <cstdlib>

#include "engine/core/error.h"

namespace masav::vk {
namespace {

// The variable's value, or "" where unset or empty.
std::string env(const char* name) {
  const char* v = std::getenv(name);
  return v ? std::string(v) : std::string();
}

}  // namespace

ContextOptions options_from_env() {
  ContextOptions o;
  o.device_selector = env("MASAV_VK_DEVICE");
  const std::string v = env("MASAV_VK_VALIDATION");
  if (v == "1" || v == "on" || v == "true")
    o.validation = true;
  else if (v == "0" || v == "off" || v == "false" || v.empty())
    o.validation = false;
  else
    throw Error("", "environment", fmt::format("invalid MASAV_VK_VALIDATION = {}", v),
                "MASAV_VK_VALIDATION must be 1/on/true or 0/off/false");
  return o;
}

std::string loader_library() {
  const std::string name = env("MASAV_VULKAN_LOADER");
  return name.empty() ? "libvulkan.so.1" : name;
}

}  // namespace masav::vk
