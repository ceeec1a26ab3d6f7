#pragma once
// Graphics pipelines from the embedded SPIR-V (shaders/render/). Every pipeline pulls its
// vertices from storage buffers (bindings 0..buffers-1, vertex and fragment stages) and takes
// push constants, so the compute kernels' buffers can be drawn without vertex-buffer usage.
#include <cstdint>
#include <memory>
#include <vector>

#include "compute/device/vk_context.h"
#include "compute/device/vk_memory.h"

namespace masav::render {

enum class Blend : uint8_t { none, alpha, additive };

struct GraphicsSpec {
  const char* vert;
  const char* frag;
  uint32_t buffers = 0;
  uint32_t push_bytes = 0;
  ::vk::PrimitiveTopology topology = ::vk::PrimitiveTopology::eTriangleList;
  bool depth_test = false;
  bool depth_write = false;
  Blend blend = Blend::none;
  bool color_write = true;              // false: a pass that only writes storage buffers (or depth)
  std::vector<vk::Texels> texels = {};  // per binding; empty: all storage buffers
};

struct GraphicsPipeline {
  uint32_t buffers = 0;
  uint32_t push_bytes = 0;
  std::vector<vk::Texels> texels;  // per binding; empty: all storage buffers
  ::vk::raii::DescriptorSetLayout set_layout = nullptr;
  ::vk::raii::PipelineLayout layout = nullptr;
  ::vk::raii::Pipeline pipeline = nullptr;
};

std::unique_ptr<GraphicsPipeline> make_graphics_pipeline(const vk::Context& ctx,
                                                         ::vk::RenderPass pass,
                                                         const GraphicsSpec& spec);

}  // namespace masav::render
