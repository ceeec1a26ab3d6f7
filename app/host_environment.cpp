#include "app/host_environment.h"

#include <fmt/format.h>

#include <cstdlib>

#include "engine/core/error.h"

namespace masav::app {
namespace {

// The variable's value, or "" where unset.
std::string variable(const char* name) {
  const char* v = std::getenv(name);
  return v ? std::string(v) : std::string();
}

}  // namespace

HostEnvironment read_host_environment() {
  HostEnvironment e;
  e.cache.masav_cache_dir = variable("MASAV_CACHE_DIR");
  e.cache.xdg_cache_home = variable("XDG_CACHE_HOME");
  e.cache.home = variable("HOME");
  e.vk_device = variable("MASAV_VK_DEVICE");
  e.vk_validation = variable("MASAV_VK_VALIDATION");
  e.vulkan_loader = variable("MASAV_VULKAN_LOADER");
  e.vk_driver_files = variable("VK_DRIVER_FILES");
  e.vk_icd_filenames = variable("VK_ICD_FILENAMES");
  return e;
}

const HostEnvironment& host_environment() {
  static const HostEnvironment env = read_host_environment();
  return env;
}

std::filesystem::path HostEnvironment::cache_dir() const {
  return resolve_cache_dir(cache).value_or(std::filesystem::path());
}

bool HostEnvironment::validation() const {
  const std::string& v = vk_validation;
  if (v == "1" || v == "on" || v == "true") return true;
  if (v == "0" || v == "off" || v == "false" || v.empty()) return false;
  throw Error("", "environment", fmt::format("invalid MASAV_VK_VALIDATION = {}", v),
              "MASAV_VK_VALIDATION must be 1/on/true or 0/off/false");
}

#if MASAV_HAVE_VULKAN
vk::ContextOptions vulkan_options(const HostEnvironment& env) {
  vk::ContextOptions o;
  o.device_selector = env.vk_device;
  o.validation = env.validation();
  if (!env.vulkan_loader.empty()) o.loader = env.vulkan_loader;
  o.driver_files = env.vk_driver_files;
  o.icd_filenames = env.vk_icd_filenames;
  return o;
}
#endif

HostRequest::HostRequest(const HostEnvironment& env, const Tuning& tuning) {
#if MASAV_HAVE_VULKAN
  vulkan_ = vulkan_options(env);
  request_.vulkan = &vulkan_;
#endif
  request_.cache_dir = env.cache_dir();
  request_.tuning = tuning;
}

}  // namespace masav::app
