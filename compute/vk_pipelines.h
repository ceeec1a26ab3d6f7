#pragma once
// Compute pipelines built from the embedded SPIR-V, specialised per device (workgroup size,
// subgroup size, loop counting, kernel constants) and cached: in memory by key, and on disk in a
// VkPipelineCache keyed by the driver's pipelineCacheUUID.
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "compute/device/vk_context.h"
#include "compute/device/vk_memory.h"
#include "compute/vk_variants.h"
#include "engine/core/device_api.h"

namespace masav::vk {

struct Kernel {
  std::string name;
  uint32_t buffers = 0;        // buffers at bindings 1..buffers (binding 0: diagnostics)
  std::vector<Texels> texels;  // per buffer; empty: all storage buffers
  uint32_t push_bytes = 0;
  ::vk::raii::DescriptorSetLayout set_layout = nullptr;
  ::vk::raii::PipelineLayout layout = nullptr;
  ::vk::raii::Pipeline pipeline = nullptr;
};

struct KernelSpec {
  const char* shader;
  uint32_t buffers;
  uint32_t push_bytes;
  SpecConstants constants;          // the shader's variant; ids 0-2 are set for every kernel
  uint32_t workgroup_size = 0;      // 0: the backend's default
  std::vector<Texels> texels = {};  // per buffer; empty: all storage buffers
};

// The descriptor type of binding b (0: diagnostics) of kernel k.
inline ::vk::DescriptorType descriptor_type(const Kernel& k, uint32_t binding) {
  return binding > 0 && binding <= k.texels.size() ? k.texels[binding - 1].descriptor_type()
                                                   : ::vk::DescriptorType::eStorageBuffer;
}

class Pipelines {
 public:
  // Counts each pipeline it creates in counters.pipelines_built. The disk cache lives in
  // cache_dir (empty: none, every run compiles again).
  Pipelines(const Context& ctx, uint32_t workgroup_size, bool count_loop_ticks,
            std::filesystem::path cache_dir, DeviceCounters& counters);
  ~Pipelines();  // writes the pipeline cache back to disk

  const Kernel& get(const KernelSpec& spec);
  uint32_t workgroup_size() const { return workgroup_size_; }

 private:
  std::string cache_path() const;

  const Context& ctx_;
  uint32_t workgroup_size_;
  bool count_loop_ticks_;
  std::filesystem::path cache_dir_;
  DeviceCounters& counters_;
  ::vk::raii::PipelineCache cache_ = nullptr;
  std::map<std::string, std::unique_ptr<Kernel>> kernels_;
};

}  // namespace masav::vk
