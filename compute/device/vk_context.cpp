#include "compute/device/vk_context.h"

#include <dlfcn.h>
#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <map>
#include <mutex>

#include "compute/device/vk_manifests.h"
#include "engine/core/error.h"

namespace masav::vk {
namespace raii = ::vk::raii;

namespace {

ValidationHandler& handler_slot() {
  static ValidationHandler h;
  return h;
}
std::atomic<uint64_t> g_validation_messages{0};

VKAPI_ATTR VkBool32 VKAPI_CALL on_debug_message(VkDebugUtilsMessageSeverityFlagBitsEXT,
                                                VkDebugUtilsMessageTypeFlagsEXT,
                                                const VkDebugUtilsMessengerCallbackDataEXT* data,
                                                void*) {
  ++g_validation_messages;
  std::string msg =
      fmt::format("[vulkan validation] {}", data && data->pMessage ? data->pMessage : "(no text)");
  if (handler_slot())
    handler_slot()(msg);
  else
    fmt::print(stderr, "{}\n", msg);
  return VK_FALSE;
}

const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";
const char* kNoDriverRemedy =
    "install mesa-vulkan-drivers (lavapipe, any CPU) or your GPU vendor's Vulkan driver; on an "
    "NVIDIA machine without a display, point VK_DRIVER_FILES at nvidia_icd.json";

// A loader library as dlopen left it: the handle, or why there is none.
struct OpenedLoader {
  void* handle = nullptr;
  std::string error;
};

// Opened with dlopen (never linked), once per process and name (ContextOptions::loader): the
// handles stay open for the process's life, as the instances made from them may.
std::unique_ptr<raii::Context> open_loader(const std::string& name) {
  static std::mutex mutex;
  static std::map<std::string, OpenedLoader> opened;
  OpenedLoader loader;
  {
    const std::lock_guard<std::mutex> lock(mutex);
    auto it = opened.find(name);
    if (it == opened.end()) {
      OpenedLoader fresh;
      fresh.handle = dlopen(name.c_str(), RTLD_NOW | RTLD_LOCAL);
      if (!fresh.handle) {
        const char* why = dlerror();
        fresh.error = why ? why : "dlopen failed";
      }
      it = opened.emplace(name, std::move(fresh)).first;
    }
    loader = it->second;
  }
  auto gipa = loader.handle ? reinterpret_cast<PFN_vkGetInstanceProcAddr>(
                                  dlsym(loader.handle, "vkGetInstanceProcAddr"))
                            : nullptr;
  if (!gipa)
    throw Error("vulkan", "",
                fmt::format("the Vulkan loader could not be opened ({})",
                            loader.error.empty() ? "no vkGetInstanceProcAddr" : loader.error),
                "install the Debian package libvulkan1, plus mesa-vulkan-drivers for the CPU "
                "driver lavapipe or your GPU vendor's driver");
  return std::make_unique<raii::Context>(gipa);
}

bool has_layer(const raii::Context& ctx, const char* name) {
  for (const auto& l : ctx.enumerateInstanceLayerProperties())
    if (std::strcmp(l.layerName, name) == 0) return true;
  return false;
}

bool has_instance_extension(const raii::Context& ctx, const std::string& name) {
  for (const auto& e : ctx.enumerateInstanceExtensionProperties())
    if (name == e.extensionName.data()) return true;
  return false;
}

// With the validation layer and the instance extensions `options` asks for, or none of them
// (`plain`: the device listing).
std::unique_ptr<raii::Instance> make_instance(const raii::Context& ctx,
                                              const ContextOptions& options, bool plain = false) {
  const bool validation = options.validation && !plain;
  static const std::vector<std::string> none;
  const std::vector<std::string>& wanted = plain ? none : options.instance_extensions;
  const uint32_t loader_version = ctx.enumerateInstanceVersion();
  if (loader_version < VK_API_VERSION_1_1)
    throw Error("vulkan", "", "the Vulkan loader only offers Vulkan 1.0",
                "install a newer libvulkan1 (masav needs Vulkan 1.1)");
  ::vk::ApplicationInfo app("masav", 1, "masav", 1, std::min(loader_version, VK_API_VERSION_1_3));
  std::vector<const char*> layers, extensions;
  if (validation) {
    if (!has_layer(ctx, kValidationLayer))
      throw Error(
          "vulkan", "",
          "validation was asked for (MASAV_VK_VALIDATION=1, or ContextOptions::validation) but "
          "VK_LAYER_KHRONOS_validation is not installed",
          "install the Debian package vulkan-validationlayers, or unset MASAV_VK_VALIDATION");
    layers.push_back(kValidationLayer);
    extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
  }
  for (const auto& e : wanted) {
    if (!has_instance_extension(ctx, e))
      throw Error("vulkan", "", fmt::format("the Vulkan loader lacks the instance extension {}", e),
                  "install mesa-vulkan-drivers and libvulkan1 with window-system support, or "
                  "render headless with `masav run`");
    extensions.push_back(e.c_str());
  }
  ::vk::InstanceCreateInfo info({}, &app, layers, extensions);
  try {
    return std::make_unique<raii::Instance>(ctx, info);
  } catch (const ::vk::SystemError& e) {
    // A manifest the environment names wrongly is the likeliest cause, whatever the loader
    // reports (a malformed one reads as ErrorOutOfHostMemory).
    if (const std::string problem =
            driver_manifest_problem(options.driver_files, options.icd_filenames);
        !problem.empty())
      throw Error("vulkan", "", fmt::format("vkCreateInstance failed: {}", problem),
                  "fix the variable or unset it (the loader then finds the installed drivers)");
    if (dynamic_cast<const ::vk::IncompatibleDriverError*>(&e))
      throw Error("vulkan", "", "no Vulkan driver is installed (the loader found no ICD)",
                  kNoDriverRemedy);
    throw Error("vulkan", "", fmt::format("vkCreateInstance failed: {}", e.what()),
                kNoDriverRemedy);
  }
}

std::string type_name(::vk::PhysicalDeviceType t) {
  switch (t) {
    case ::vk::PhysicalDeviceType::eDiscreteGpu:
      return "discrete";
    case ::vk::PhysicalDeviceType::eIntegratedGpu:
      return "integrated";
    case ::vk::PhysicalDeviceType::eVirtualGpu:
      return "virtual";
    case ::vk::PhysicalDeviceType::eCpu:
      return "cpu";
    default:
      return "other";
  }
}

int type_rank(::vk::PhysicalDeviceType t) {
  switch (t) {
    case ::vk::PhysicalDeviceType::eDiscreteGpu:
      return 0;
    case ::vk::PhysicalDeviceType::eIntegratedGpu:
      return 1;
    case ::vk::PhysicalDeviceType::eVirtualGpu:
      return 2;
    case ::vk::PhysicalDeviceType::eCpu:
      return 4;
    default:
      return 3;
  }
}

std::string vendor_name(uint32_t id) {
  switch (id) {
    case 0x10DE:
      return "NVIDIA";
    case 0x1002:
      return "AMD";
    case 0x8086:
      return "Intel";
    case 0x10005:
      return "Mesa";
    case 0x13B5:
      return "ARM";
    case 0x5143:
      return "Qualcomm";
    case 0x106B:
      return "Apple";
    default:
      return fmt::format("0x{:04x}", id);
  }
}

std::string version_string(uint32_t v) {
  return fmt::format("{}.{}.{}", VK_API_VERSION_MAJOR(v), VK_API_VERSION_MINOR(v),
                     VK_API_VERSION_PATCH(v));
}

// A queue family with compute and timestamps, graphics too when there is one (for rendering).
// With `graphics`, only families that also draw (and present, if `present` is given) qualify.
std::optional<uint32_t> pick_queue_family(const raii::PhysicalDevice& pd, bool graphics = false,
                                          const PresentSupport& present = {},
                                          VkInstance instance = VK_NULL_HANDLE) {
  std::optional<uint32_t> compute_only;
  const auto families = pd.getQueueFamilyProperties();
  for (uint32_t i = 0; i < families.size(); ++i) {
    const auto& f = families[i];
    if (!(f.queueFlags & ::vk::QueueFlagBits::eCompute) || f.timestampValidBits == 0) continue;
    if (f.queueFlags & ::vk::QueueFlagBits::eGraphics) {
      if (present && !present(instance, static_cast<VkPhysicalDevice>(*pd), i)) continue;
      return i;
    }
    if (!compute_only && !graphics) compute_only = i;
  }
  return compute_only;
}

// Why masav cannot use this device, or "" if it can.
std::string unusable_reason(const raii::PhysicalDevice& pd) {
  const auto props = pd.getProperties();
  if (props.apiVersion < VK_API_VERSION_1_1) return "supports only Vulkan 1.0 (masav needs 1.1)";
  if (!pick_queue_family(pd)) return "no compute queue with timestamps";
  const auto chain =
      pd.getProperties2<::vk::PhysicalDeviceProperties2, ::vk::PhysicalDeviceSubgroupProperties>();
  const auto& sg = chain.get<::vk::PhysicalDeviceSubgroupProperties>();
  if (!(sg.supportedStages & ::vk::ShaderStageFlagBits::eCompute))
    return "no subgroup operations in compute shaders";
  // Shuffles carry the SPH kernels' cooperative neighbour walk (every desktop driver has them).
  const auto need = ::vk::SubgroupFeatureFlagBits::eBasic |
                    ::vk::SubgroupFeatureFlagBits::eArithmetic |
                    ::vk::SubgroupFeatureFlagBits::eShuffle;
  if ((sg.supportedOperations & need) != need) return "no subgroup arithmetic or shuffle";
  if (sg.subgroupSize < 4 || sg.subgroupSize > 128)
    return fmt::format("subgroup size {} outside [4, 128]", sg.subgroupSize);
  if (props.limits.maxComputeSharedMemorySize < 16384) return "less than 16 KiB shared memory";
  if (props.limits.maxComputeWorkGroupInvocations < 256) return "workgroups below 256 invocations";
  return "";
}

// Why this device cannot render as `options` asks (graphics queue, presentation, extensions),
// or "" if it can.
std::string render_unusable_reason(const raii::PhysicalDevice& pd, const ContextOptions& options,
                                   VkInstance instance) {
  if (!options.graphics) return "";
  if (!pick_queue_family(pd, true)) return "no queue that both computes and draws";
  if (options.present_support && !pick_queue_family(pd, true, options.present_support, instance))
    return "cannot present to this window";
  const auto available = pd.enumerateDeviceExtensionProperties();
  for (const auto& want : options.device_extensions) {
    bool found = false;
    for (const auto& e : available) found = found || want == e.extensionName.data();
    if (!found) return "no " + want;
  }
  return "";
}

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

}  // namespace

void set_validation_handler(ValidationHandler handler) {
  handler_slot() = std::move(handler);
}
uint64_t validation_message_count() {
  return g_validation_messages.load();
}

std::vector<DeviceListing> Context::list_devices(const ContextOptions& options) {
  auto ctx = open_loader(options.loader);
  auto instance = make_instance(*ctx, options, true);
  raii::PhysicalDevices devices(*instance);
  std::vector<DeviceListing> out;
  for (uint32_t i = 0; i < devices.size(); ++i) {
    const auto props = devices[i].getProperties();
    DeviceListing l;
    l.index = i;
    l.name = props.deviceName.data();
    l.type = type_name(props.deviceType);
    l.api_version = version_string(props.apiVersion);
    l.reason = unusable_reason(devices[i]);
    l.usable = l.reason.empty();
    l.rank = type_rank(props.deviceType);
    out.push_back(l);
  }
  return out;
}

Context::Context(const ContextOptions& options) {
  context_ = open_loader(options.loader);
  instance_ = make_instance(*context_, options);
  graphics_ = options.graphics;
  const VkInstance raw_instance = static_cast<VkInstance>(**instance_);
  auto why_not = [&](const raii::PhysicalDevice& pd) {
    std::string why = unusable_reason(pd);
    return why.empty() ? render_unusable_reason(pd, options, raw_instance) : why;
  };
  if (options.validation) {
    using S = ::vk::DebugUtilsMessageSeverityFlagBitsEXT;
    using T = ::vk::DebugUtilsMessageTypeFlagBitsEXT;
    ::vk::DebugUtilsMessengerCreateInfoEXT info({}, S::eWarning | S::eError,
                                                T::eGeneral | T::eValidation | T::ePerformance,
                                                &on_debug_message);
    messenger_ = std::make_unique<raii::DebugUtilsMessengerEXT>(*instance_, info);
  }

  raii::PhysicalDevices devices(*instance_);
  if (devices.empty())
    throw Error("vulkan", "", "the Vulkan loader found no device (no driver installed)",
                kNoDriverRemedy);

  // Choose: the selector if given, else the best-ranked usable device.
  std::optional<size_t> chosen;
  std::string listing;
  for (size_t i = 0; i < devices.size(); ++i)
    listing +=
        fmt::format("{}{}: {}", i ? ", " : "", i, devices[i].getProperties().deviceName.data());
  if (!options.device_selector.empty()) {
    const std::string sel = options.device_selector;
    char* end = nullptr;
    const long idx = std::strtol(sel.c_str(), &end, 10);
    if (end && *end == '\0') {
      if (idx < 0 || size_t(idx) >= devices.size())
        throw_invalid("vulkan", "device", sel,
                      fmt::format("an index in [0, {}] ({})", devices.size() - 1, listing));
      chosen = size_t(idx);
    } else {
      for (size_t i = 0; i < devices.size() && !chosen; ++i)
        if (lower(devices[i].getProperties().deviceName.data()).find(lower(sel)) !=
            std::string::npos)
          chosen = i;
      if (!chosen)
        throw_invalid("vulkan", "device", sel,
                      fmt::format("an index or part of a name ({})", listing));
    }
    const std::string why = why_not(devices[*chosen]);
    if (!why.empty())
      throw Error("vulkan", "",
                  fmt::format("device '{}' cannot run masav: {}",
                              devices[*chosen].getProperties().deviceName.data(), why),
                  "choose another device (masav info lists them)");
  } else {
    int best_rank = 1 << 30;
    for (size_t i = 0; i < devices.size(); ++i) {
      if (!why_not(devices[i]).empty()) continue;
      const int r = type_rank(devices[i].getProperties().deviceType);
      if (r < best_rank) best_rank = r, chosen = i;
    }
    if (!chosen) {
      std::string reasons;
      for (size_t i = 0; i < devices.size(); ++i)
        reasons += fmt::format("{}{}: {}", i ? "; " : "",
                               devices[i].getProperties().deviceName.data(), why_not(devices[i]));
      throw Error("vulkan", "", fmt::format("no usable Vulkan device ({})", reasons),
                  options.graphics
                      ? "masav renders with Vulkan 1.1 on a queue that computes and draws; "
                        "mesa-vulkan-drivers (lavapipe) provides one on any CPU"
                      : "masav needs Vulkan 1.1 with subgroup arithmetic and shuffle in compute "
                        "shaders; mesa-vulkan-drivers (lavapipe) provides it on any CPU");
    }
  }
  physical_ = std::make_unique<raii::PhysicalDevice>(std::move(devices[*chosen]));

  const auto props = physical_->getProperties();
  queue_family_ =
      *pick_queue_family(*physical_, options.graphics, options.present_support, raw_instance);
  timestamp_bits_ = physical_->getQueueFamilyProperties()[queue_family_].timestampValidBits;
  std::memcpy(cache_uuid_.data(), props.pipelineCacheUUID.data(), VK_UUID_SIZE);

  const float priority = 1.0f;
  ::vk::DeviceQueueCreateInfo qinfo({}, queue_family_, 1, &priority);
  std::vector<const char*> device_extensions;
  for (const auto& e : options.device_extensions) device_extensions.push_back(e.c_str());
  ::vk::PhysicalDeviceFeatures features;
  if (options.graphics) {
    // Point sprites larger than one pixel need largePoints (every desktop driver and lavapipe).
    features.largePoints = physical_->getFeatures().largePoints;
    max_point_size_ = features.largePoints ? props.limits.pointSizeRange[1] : 1.0f;
    // The fluid surface splats particles into storage buffers from fragment shaders.
    features.fragmentStoresAndAtomics = physical_->getFeatures().fragmentStoresAndAtomics;
    fragment_stores_ = features.fragmentStoresAndAtomics;
  }
  ::vk::DeviceCreateInfo dinfo({}, qinfo, {}, device_extensions, &features);
  try {
    device_ = std::make_unique<raii::Device>(*physical_, dinfo);
  } catch (const ::vk::SystemError& e) {
    throw Error("vulkan", "",
                fmt::format("vkCreateDevice failed on {}: {}", props.deviceName.data(), e.what()),
                kNoDriverRemedy);
  }
  queue_ = std::make_unique<raii::Queue>(*device_, queue_family_, 0);

  // Capabilities.
  const auto chain =
      physical_
          ->getProperties2<::vk::PhysicalDeviceProperties2, ::vk::PhysicalDeviceSubgroupProperties,
                           ::vk::PhysicalDeviceMaintenance3Properties>();
  const auto& sg = chain.get<::vk::PhysicalDeviceSubgroupProperties>();
  const auto& m3 = chain.get<::vk::PhysicalDeviceMaintenance3Properties>();
  caps_.backend = "vulkan";
  caps_.device_name = props.deviceName.data();
  caps_.vendor = vendor_name(props.vendorID);
  caps_.device_type = type_name(props.deviceType);
  caps_.driver = fmt::format("Vulkan {}, driver 0x{:x}", version_string(props.apiVersion),
                             props.driverVersion);
  caps_.subgroup_size = sg.subgroupSize;
  subgroup_ballot_ = bool(sg.supportedOperations & ::vk::SubgroupFeatureFlagBits::eBallot);
  caps_.min_subgroup_size = sg.subgroupSize;
  if (props.apiVersion >= VK_API_VERSION_1_3) {
    const auto c13 = physical_->getProperties2<::vk::PhysicalDeviceProperties2,
                                               ::vk::PhysicalDeviceSubgroupSizeControlProperties,
                                               ::vk::PhysicalDeviceDriverProperties>();
    caps_.min_subgroup_size =
        c13.get<::vk::PhysicalDeviceSubgroupSizeControlProperties>().minSubgroupSize;
    const auto& drv = c13.get<::vk::PhysicalDeviceDriverProperties>();
    caps_.driver = fmt::format("{} {} (Vulkan {})", drv.driverName.data(), drv.driverInfo.data(),
                               version_string(props.apiVersion));
  }
  caps_.max_workgroup_size = props.limits.maxComputeWorkGroupInvocations;
  max_texel_buffer_elements_ = props.limits.maxTexelBufferElements;
  if (const uint64_t cap = options.max_texels; cap && cap < max_texel_buffer_elements_)
    max_texel_buffer_elements_ = cap;
  caps_.max_workgroups_x = props.limits.maxComputeWorkGroupCount[0];
  caps_.shared_memory_bytes = props.limits.maxComputeSharedMemorySize;
  caps_.max_buffer_bytes =
      std::min<uint64_t>(props.limits.maxStorageBufferRange, m3.maxMemoryAllocationSize);
  if (const uint64_t cap = options.max_buffer_bytes; cap && cap < caps_.max_buffer_bytes)
    caps_.max_buffer_bytes = cap;
  uint64_t largest_heap = 0;
  const auto mem = physical_->getMemoryProperties();
  for (uint32_t h = 0; h < mem.memoryHeapCount; ++h)
    if (mem.memoryHeaps[h].flags & ::vk::MemoryHeapFlagBits::eDeviceLocal)
      largest_heap = std::max<uint64_t>(largest_heap, mem.memoryHeaps[h].size);
  caps_.device_memory_bytes = largest_heap;
  caps_.timestamp_period_ns = props.limits.timestampPeriod;
  caps_.real_is_double = false;
  caps_.threads = 1;
}

Context::~Context() = default;

}  // namespace masav::vk
