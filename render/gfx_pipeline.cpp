#include "render/gfx_pipeline.h"

#include <fmt/format.h>

#include <vector>

#include "engine/core/error.h"
#include "shaders/embedded.h"

namespace masav::render {
namespace {

::vk::raii::ShaderModule module(const vk::Context& ctx, const char* name) {
  const auto words = shaders::find(name);
  if (words.empty())
    throw Error("render", name, "no embedded SPIR-V for this shader",
                "rebuild masav (the shaders are compiled into the binary)");
  return ::vk::raii::ShaderModule(
      ctx.device(), ::vk::ShaderModuleCreateInfo({}, words.size_bytes(), words.data()));
}

}  // namespace

std::unique_ptr<GraphicsPipeline> make_graphics_pipeline(const vk::Context& ctx,
                                                         ::vk::RenderPass pass,
                                                         const GraphicsSpec& spec) {
  using Stage = ::vk::ShaderStageFlagBits;
  auto p = std::make_unique<GraphicsPipeline>();
  p->buffers = spec.buffers;
  p->push_bytes = spec.push_bytes;
  p->texels = spec.texels;
  p->texels.resize(spec.buffers);  // the rest storage buffers
  std::vector<::vk::DescriptorSetLayoutBinding> bindings;
  for (uint32_t b = 0; b < spec.buffers; ++b)
    bindings.emplace_back(b, p->texels[b].descriptor_type(), 1, Stage::eVertex | Stage::eFragment);
  p->set_layout = ::vk::raii::DescriptorSetLayout(
      ctx.device(), ::vk::DescriptorSetLayoutCreateInfo({}, bindings));
  const ::vk::PushConstantRange range(Stage::eVertex | Stage::eFragment, 0, spec.push_bytes);
  const ::vk::DescriptorSetLayout set_layout = *p->set_layout;
  ::vk::PipelineLayoutCreateInfo linfo({}, set_layout);
  if (spec.push_bytes) linfo.setPushConstantRanges(range);
  p->layout = ::vk::raii::PipelineLayout(ctx.device(), linfo);

  const auto vert = module(ctx, spec.vert);
  const auto frag = module(ctx, spec.frag);
  const ::vk::PipelineShaderStageCreateInfo stages[2] = {{{}, Stage::eVertex, *vert, "main"},
                                                         {{}, Stage::eFragment, *frag, "main"}};
  const ::vk::PipelineVertexInputStateCreateInfo vertex_input;
  const ::vk::PipelineInputAssemblyStateCreateInfo assembly({}, spec.topology);
  const ::vk::PipelineViewportStateCreateInfo viewport({}, 1, nullptr, 1, nullptr);
  ::vk::PipelineRasterizationStateCreateInfo raster;
  raster.setPolygonMode(::vk::PolygonMode::eFill)
      .setCullMode(::vk::CullModeFlagBits::eNone)
      .setLineWidth(1.0f);
  const ::vk::PipelineMultisampleStateCreateInfo multisample;
  ::vk::PipelineDepthStencilStateCreateInfo depth;
  depth.setDepthTestEnable(spec.depth_test)
      .setDepthWriteEnable(spec.depth_write)
      .setDepthCompareOp(::vk::CompareOp::eLessOrEqual);
  ::vk::PipelineColorBlendAttachmentState blend;
  using F = ::vk::BlendFactor;
  if (spec.color_write)
    blend.setColorWriteMask(::vk::ColorComponentFlagBits::eR | ::vk::ColorComponentFlagBits::eG |
                            ::vk::ColorComponentFlagBits::eB | ::vk::ColorComponentFlagBits::eA);
  if (spec.blend == Blend::alpha)
    blend.setBlendEnable(true)
        .setSrcColorBlendFactor(F::eSrcAlpha)
        .setDstColorBlendFactor(F::eOneMinusSrcAlpha)
        .setSrcAlphaBlendFactor(F::eOne)
        .setDstAlphaBlendFactor(F::eOneMinusSrcAlpha);
  else if (spec.blend == Blend::additive)
    blend.setBlendEnable(true)
        .setSrcColorBlendFactor(F::eOne)
        .setDstColorBlendFactor(F::eOne)
        .setSrcAlphaBlendFactor(F::eOne)
        .setDstAlphaBlendFactor(F::eOne);
  const ::vk::PipelineColorBlendStateCreateInfo blending({}, false, ::vk::LogicOp::eCopy, blend);
  const ::vk::DynamicState dynamic_states[2] = {::vk::DynamicState::eViewport,
                                                ::vk::DynamicState::eScissor};
  const ::vk::PipelineDynamicStateCreateInfo dynamic({}, dynamic_states);
  const ::vk::GraphicsPipelineCreateInfo info({}, stages, &vertex_input, &assembly, nullptr,
                                              &viewport, &raster, &multisample, &depth, &blending,
                                              &dynamic, *p->layout, pass, 0);
  try {
    p->pipeline = ::vk::raii::Pipeline(ctx.device(), nullptr, info);
  } catch (const ::vk::SystemError& e) {
    throw Error("render", spec.vert, fmt::format("pipeline creation failed: {}", e.what()),
                "update the Vulkan driver; if it persists, report the device and driver");
  }
  return p;
}

}  // namespace masav::render
