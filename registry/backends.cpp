#include "registry/backends.h"

#include <fmt/format.h>

#include "engine/core/error.h"
#include "engine/cpu/cpu_backend.h"
#if MASAV_HAVE_VULKAN
#include "compute/device/vk_context.h"
#include "compute/vk_factory.h"
#endif
#if MASAV_HAVE_CUDA
#include "cuda_ref/cuda_factory.h"
#endif

namespace masav {
namespace {

[[maybe_unused]] BackendStatus not_built(const std::string& name, const std::string& how) {
  BackendStatus s;
  s.name = name;
  s.reason = fmt::format("not built into this binary ({})", how);
  return s;
}

BackendStatus cpu_status() {
  BackendStatus s;
  s.name = "cpu";
  s.built = s.available = true;
  cpu::CpuBackend probe(1);
  DeviceStatus d;
  d.name = probe.caps().device_name;
  d.type = "cpu";
  d.detail = fmt::format("{} threads, fp64 reference", cpu::default_cpu_threads());
  d.usable = true;
  s.devices.push_back(d);
  return s;
}

BackendStatus status_of(const std::string& name, [[maybe_unused]] const BackendRequest& request) {
  if (name == "cpu") return cpu_status();
  if (name == "vulkan") {
#if MASAV_HAVE_VULKAN
    return vk::backend_status(request);
#else
    return not_built("vulkan", "configure with -DMASAV_WITH_VULKAN=ON and libvulkan-dev");
#endif
  }
#if MASAV_HAVE_CUDA
  return cuda::backend_status();
#else
  return not_built("cuda", "configure with -DMASAV_WITH_CUDA=ON on a machine with nvcc");
#endif
}

}  // namespace

const std::vector<std::string>& backend_names() {
  static const std::vector<std::string> names = {"vulkan", "cuda", "cpu"};
  return names;
}

std::vector<BackendStatus> list_backends(const BackendRequest& request) {
  std::vector<BackendStatus> out;
  for (const auto& n : backend_names()) out.push_back(status_of(n, request));
  return out;
}

std::string auto_backend_name(const BackendRequest& request) {
  if (status_of("cuda", request).available) return "cuda";
  if (status_of("vulkan", request).available) return "vulkan";
  return "cpu";
}

std::unique_ptr<Backend> create_backend(std::string_view name_in, std::string_view device,
                                        const BackendRequest& request) {
  const std::string name = name_in == "auto" ? auto_backend_name(request) : std::string(name_in);
  if (name == "cpu") {
    if (!device.empty() && device != "0")
      throw_invalid(
          "cpu backend", "device", std::string(device),
          "empty or 0 (the CPU backend has one device; --tune cpu.threads=N sets its threads)");
    // A CPU device renders like the GPUs, in fp32; the reference (CpuBackend's default) in fp64.
    const unsigned threads = request.tuning.cpu.threads;
    return std::make_unique<cpu::CpuBackend>(threads ? threads : cpu::default_cpu_threads(),
                                             cpu::CpuRenderPrecision::fp32, request.tuning);
  }
  if (name == "vulkan") {
#if MASAV_HAVE_VULKAN
    return vk::create_backend(device, request);
#else
    throw Error("vulkan", "", status_of("vulkan", request).reason, "use --backend cpu, or rebuild");
#endif
  }
  if (name == "cuda") {
#if MASAV_HAVE_CUDA
    return cuda::create_backend(device, request.tuning);
#else
    throw Error("cuda", "", status_of("cuda", request).reason,
                "use --backend vulkan or cpu, or rebuild");
#endif
  }
  throw_invalid("backend selection", "backend", std::string(name_in),
                "one of vulkan, cuda, cpu, auto");
}

namespace {

#if MASAV_HAVE_VULKAN
using VulkanStorage = vk::ContextOptions;
#else
struct VulkanStorage {};  // no Vulkan backend: nothing to set
#endif

// `request` with the Vulkan options of `vulkan`, held by `storage` (which outlives its use).
BackendRequest with_vulkan(BackendRequest request, [[maybe_unused]] const VulkanSettings& vulkan,
                           [[maybe_unused]] VulkanStorage& storage) {
#if MASAV_HAVE_VULKAN
  storage.validation = vulkan.validation;
  storage.loader = vulkan.loader;
  request.vulkan = &storage;
#endif
  return request;
}

}  // namespace

std::unique_ptr<Backend> create_backend(std::string_view name, std::string_view device,
                                        const BackendRequest& request,
                                        const VulkanSettings& vulkan) {
  VulkanStorage storage;
  return create_backend(name, device, with_vulkan(request, vulkan, storage));
}

std::vector<BackendStatus> list_backends(const VulkanSettings& vulkan) {
  VulkanStorage storage;
  return list_backends(with_vulkan(BackendRequest{}, vulkan, storage));
}

namespace {

class Registry final : public BackendFactory {
 public:
  std::vector<BackendStatus> list(const BackendRequest& request) const override {
    return list_backends(request);
  }
  std::unique_ptr<Backend> create(std::string_view name, std::string_view device,
                                  const BackendRequest& request) const override {
    return create_backend(name, device, request);
  }
};

}  // namespace

const BackendFactory& backend_factory() {
  static const Registry registry;
  return registry;
}

}  // namespace masav
