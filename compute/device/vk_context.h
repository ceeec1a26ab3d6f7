#pragma once
// Instance, physical-device choice and logical device for the Vulkan backend.
// Devices are ranked discrete > integrated > virtual > other > CPU (lavapipe last); a selector
// (index as listed by `masav info`, or a case-insensitive part of the name) overrides the rank.
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "compute/device/vk_common.h"
#include "engine/core/capabilities.h"

namespace masav::vk {

struct DeviceListing {
  uint32_t index = 0;  // enumeration order
  std::string name;
  std::string type;
  std::string api_version;
  bool usable = false;
  std::string reason;  // why not usable
  int rank = 0;        // lower is preferred
};

// Whether a queue family of a device can present to the window (glfwGetPhysicalDevice-
// PresentationSupport); used to pick the device and queue when rendering to a window.
using PresentSupport = std::function<bool(VkInstance, VkPhysicalDevice, uint32_t family)>;

// Everything from the caller: the library never reads the process environment (the masav
// command line fills these from MASAV_VK_DEVICE, MASAV_VK_VALIDATION, MASAV_VULKAN_LOADER,
// VK_DRIVER_FILES and VK_ICD_FILENAMES; docs/backends.md).
struct ContextOptions {
  std::string device_selector;  // "" = best ranked
  bool validation = false;      // VK_LAYER_KHRONOS_validation with a debug messenger
  // The Vulkan loader library dlopen opens (a path, or a name the dynamic linker searches);
  // the tests name a missing one to play a machine without Vulkan.
  std::string loader = "libvulkan.so.1";
  // The values of the loader's own variables VK_DRIVER_FILES and VK_ICD_FILENAMES ("" = unset),
  // which the loader reads itself: masav only reads them here to say which manifest is wrong
  // when vkCreateInstance fails (compute/device/vk_manifests.h).
  std::string driver_files;
  std::string icd_filenames;
  // Device limits lowered, never raised (0: the device's own): VulkanTuning::max_buffer_mib and
  // max_texels, so that the refusal of a size too large is tested the same on every device.
  uint64_t max_buffer_bytes = 0;  // the largest buffer a kernel may bind
  uint64_t max_texels = 0;        // the most texels a uniform texel buffer may span
  // Rendering (render/): a graphics queue and large points are required; instance and device
  // extensions for a window surface and swapchain; present_support restricts the choice to
  // devices and queues that can show the window.
  bool graphics = false;
  std::vector<std::string> instance_extensions;
  std::vector<std::string> device_extensions;
  PresentSupport present_support;
};

// Called for every validation message; default prints to stderr. Tests install one that fails.
using ValidationHandler = std::function<void(const std::string&)>;
void set_validation_handler(ValidationHandler handler);
uint64_t validation_message_count();

class Context {
 public:
  explicit Context(const ContextOptions& options);
  ~Context();

  // Lists every physical device with whether masav can use it, through the loader `options`
  // name (throws masav::Error when there is no loader or no driver at all). Only the loader and
  // the manifest variables are read: the listing names every device.
  static std::vector<DeviceListing> list_devices(const ContextOptions& options = {});

  const ::vk::raii::Instance& instance() const { return *instance_; }
  const ::vk::raii::Device& device() const { return *device_; }
  const ::vk::raii::PhysicalDevice& physical() const { return *physical_; }
  const ::vk::raii::Queue& queue() const { return *queue_; }
  uint32_t queue_family() const { return queue_family_; }
  const Capabilities& caps() const { return caps_; }
  uint32_t timestamp_valid_bits() const { return timestamp_bits_; }
  std::array<uint8_t, VK_UUID_SIZE> pipeline_cache_uuid() const { return cache_uuid_; }
  bool subgroup_ballot() const { return subgroup_ballot_; }
  bool graphics() const { return graphics_; }
  float max_point_size() const { return max_point_size_; }
  // Fragment shaders may write storage buffers (graphics contexts; the fluid surface needs it).
  bool fragment_stores() const { return fragment_stores_; }
  // The most texels a uniform texel buffer's view may span.
  uint64_t max_texel_buffer_elements() const { return max_texel_buffer_elements_; }

 private:
  std::unique_ptr<::vk::raii::Context> context_;
  std::unique_ptr<::vk::raii::Instance> instance_;
  std::unique_ptr<::vk::raii::DebugUtilsMessengerEXT> messenger_;
  std::unique_ptr<::vk::raii::PhysicalDevice> physical_;
  std::unique_ptr<::vk::raii::Device> device_;
  std::unique_ptr<::vk::raii::Queue> queue_;
  uint32_t queue_family_ = 0;
  uint32_t timestamp_bits_ = 0;
  bool subgroup_ballot_ = false;
  bool graphics_ = false;
  float max_point_size_ = 1.0f;
  bool fragment_stores_ = false;
  uint64_t max_texel_buffer_elements_ = 0;
  std::array<uint8_t, VK_UUID_SIZE> cache_uuid_{};
  Capabilities caps_;
};

}  // namespace masav::vk
