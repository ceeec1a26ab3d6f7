#include "compute/vk_pipelines.h"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <optional>

#include "engine/core/error.h"
#include "engine/util/cache_file.h"
#include "shaders/embedded.h"
#include "shaders/spec_ids.h"

namespace masav::vk {

namespace {

// Pipeline caches are a few MiB; a file declaring more is not read.
constexpr uint64_t kMaxPipelineCacheBytes = uint64_t(256) << 20;

// The driver checks its own header in the blob, but not that the rest is intact: our checked
// envelope (engine/util/cache_file.h) does.
CacheFileId pipeline_cache_id(const std::string& path) {
  return {"vk-pipeline-cache", 1, std::filesystem::path(path).filename().string()};
}

}  // namespace

std::string Pipelines::cache_path() const {
  if (cache_dir_.empty()) return "";
  std::string uuid;
  for (uint8_t b : ctx_.pipeline_cache_uuid()) uuid += fmt::format("{:02x}", b);
  return fmt::format("{}/vk_pipelines_{}.bin", cache_dir_.string(), uuid);
}

Pipelines::Pipelines(const Context& ctx, uint32_t workgroup_size, bool count_loop_ticks,
                     std::filesystem::path cache_dir, DeviceCounters& counters)
    : ctx_(ctx),
      workgroup_size_(workgroup_size),
      count_loop_ticks_(count_loop_ticks),
      cache_dir_(std::move(cache_dir)),
      counters_(counters) {
  // The driver validates the blob's header against its own UUID and ignores a stale one.
  const std::string path = cache_path();
  const std::optional<std::string> blob =
      path.empty() ? std::nullopt
                   : load_cache_file(path, pipeline_cache_id(path), kMaxPipelineCacheBytes);
  ::vk::PipelineCacheCreateInfo info({}, blob ? blob->size() : 0, blob ? blob->data() : nullptr);
  try {
    cache_ = ::vk::raii::PipelineCache(ctx_.device(), info);
  } catch (const ::vk::SystemError&) {
    cache_ = ::vk::raii::PipelineCache(ctx_.device(), ::vk::PipelineCacheCreateInfo());
  }
}

Pipelines::~Pipelines() {
  // Best effort: a cache that cannot be written only costs compile time on the next start.
  try {
    const std::string path = cache_path();
    if (path.empty() || kernels_.empty()) return;
    const std::vector<uint8_t> data = cache_.getData();
    write_cache_file(path, pipeline_cache_id(path),
                     std::string_view(reinterpret_cast<const char*>(data.data()), data.size()));
  } catch (...) {
  }
}

const Kernel& Pipelines::get(const KernelSpec& spec) {
  const uint32_t wg = spec.workgroup_size ? spec.workgroup_size : workgroup_size_;
  // By id, so that the order a caller names them in does not matter.
  SpecConstants constants = spec.constants;
  std::sort(constants.begin(), constants.end(),
            [](const SpecConstant& a, const SpecConstant& b) { return a.id < b.id; });
  std::string key = fmt::format("{}/{}", spec.shader, wg);
  for (size_t i = 0; i < constants.size(); ++i) {
    if (constants[i].id < kSpecFirstVariant || (i > 0 && constants[i].id == constants[i - 1].id))
      throw Error("vulkan", spec.shader,
                  fmt::format("specialisation constant {} set twice, or one of 0-2 that "
                              "every kernel has (shaders/spec_ids.h)",
                              constants[i].id),
                  "internal error: report it");
    key += fmt::format(":{}={}", constants[i].id, constants[i].value);
  }
  for (const Texels& t : spec.texels) key += fmt::format("/t{}", uint32_t(t.format));
  if (auto it = kernels_.find(key); it != kernels_.end()) return *it->second;

  const auto words = shaders::find(spec.shader);
  if (words.empty())
    throw Error("vulkan", spec.shader, "no embedded SPIR-V for this kernel",
                "rebuild masav (the shaders are compiled into the binary)");

  auto k = std::make_unique<Kernel>();
  k->name = spec.shader;
  k->buffers = spec.buffers;
  k->push_bytes = spec.push_bytes;
  k->texels = spec.texels;
  if (!k->texels.empty() && k->texels.size() != spec.buffers)
    throw Error("vulkan", spec.shader, "texel formats given for some buffers only",
                "internal error: report it");
  std::vector<::vk::DescriptorSetLayoutBinding> bindings;
  for (uint32_t b = 0; b <= spec.buffers; ++b)
    bindings.emplace_back(b, descriptor_type(*k, b), 1, ::vk::ShaderStageFlagBits::eCompute);
  k->set_layout = ::vk::raii::DescriptorSetLayout(
      ctx_.device(), ::vk::DescriptorSetLayoutCreateInfo({}, bindings));
  ::vk::PushConstantRange range(::vk::ShaderStageFlagBits::eCompute, 0, spec.push_bytes);
  ::vk::DescriptorSetLayout set_layout = *k->set_layout;
  ::vk::PipelineLayoutCreateInfo linfo({}, set_layout);
  if (spec.push_bytes) linfo.setPushConstantRanges(range);
  k->layout = ::vk::raii::PipelineLayout(ctx_.device(), linfo);

  ::vk::ShaderModuleCreateInfo minfo({}, words.size_bytes(), words.data());
  ::vk::raii::ShaderModule module(ctx_.device(), minfo);

  // Every kernel's constants (shaders/common/kernel_base.glsl), then its variant's.
  SpecConstants all = {{kSpecWorkgroupSize, wg},
                       {kSpecSubgroupMin, ctx_.caps().min_subgroup_size},
                       {kSpecCountLoopTicks, count_loop_ticks_ ? 1u : 0u}};
  all.insert(all.end(), constants.begin(), constants.end());
  std::vector<uint32_t> values;
  std::vector<::vk::SpecializationMapEntry> entries;
  for (const SpecConstant& c : all) {
    entries.emplace_back(c.id, uint32_t(4 * values.size()), 4);
    values.push_back(c.value);
  }
  ::vk::SpecializationInfo sinfo(entries, ::vk::ArrayProxyNoTemporaries<const uint32_t>(values));
  ::vk::PipelineShaderStageCreateInfo stage({}, ::vk::ShaderStageFlagBits::eCompute, *module,
                                            "main", &sinfo);
  ::vk::ComputePipelineCreateInfo cinfo({}, stage, *k->layout);
  try {
    k->pipeline = ::vk::raii::Pipeline(ctx_.device(), cache_, cinfo);
  } catch (const ::vk::SystemError& e) {
    throw Error("vulkan", spec.shader, fmt::format("pipeline creation failed: {}", e.what()),
                "update the Vulkan driver; if it persists, report the device and driver");
  }
  ++counters_.pipelines_built;
  return *kernels_.emplace(key, std::move(k)).first->second;
}

}  // namespace masav::vk
