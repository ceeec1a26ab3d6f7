#pragma once
// Compute pipelines built from the embedded SPIR-V, specialised per device (workgroup size,
// subgroup size, loop counting, kernel constants) and cached: in memory by key, and on disk in a
// VkPipelineCache keyed by the driver's pipelineCacheUUID.
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "compute/device/vk_context.h"

namespace masav::vk {

struct Kernel {
  std::string name;
  uint32_t buffers = 0;  // storage buffers at bindings 1..buffers (binding 0: diagnostics)
  uint32_t push_bytes = 0;
  ::vk::raii::DescriptorSetLayout set_layout = nullptr;
  ::vk::raii::PipelineLayout layout = nullptr;
  ::vk::raii::Pipeline pipeline = nullptr;
};

struct KernelSpec {
  const char* shader;
  uint32_t buffers;
  uint32_t push_bytes;
  std::vector<uint32_t> constants;  // specialization constants 3, 4, ...
  uint32_t workgroup_size = 0;      // 0: the backend's default
};

class Pipelines {
 public:
  Pipelines(const Context& ctx, uint32_t workgroup_size, bool count_loop_ticks);
  ~Pipelines();  // writes the pipeline cache back to disk

  const Kernel& get(const KernelSpec& spec);
  uint32_t workgroup_size() const { return workgroup_size_; }

 private:
  std::string cache_path() const;

  const Context& ctx_;
  uint32_t workgroup_size_;
  bool count_loop_ticks_;
  ::vk::raii::PipelineCache cache_ = nullptr;
  std::map<std::string, std::unique_ptr<Kernel>> kernels_;
};

}  // namespace masav::vk
