#include "compute/device/vk_commands.h"

#include <fmt/format.h>

#include <string>

#include "engine/core/error.h"

namespace masav::vk {

Commands::Commands(const Context& ctx) : ctx_(ctx) {
  pool_ = ::vk::raii::CommandPool(
      ctx_.device(),
      ::vk::CommandPoolCreateInfo(::vk::CommandPoolCreateFlagBits::eResetCommandBuffer,
                                  ctx_.queue_family()));
  ::vk::raii::CommandBuffers bufs(
      ctx_.device(),
      ::vk::CommandBufferAllocateInfo(*pool_, ::vk::CommandBufferLevel::ePrimary, 1));
  cmd_ = std::move(bufs.front());
  fence_ = ::vk::raii::Fence(ctx_.device(), ::vk::FenceCreateInfo());
}

const ::vk::raii::CommandBuffer& Commands::begin() {
  if (!recording_) {
    cmd_.reset();
    cmd_.begin(::vk::CommandBufferBeginInfo(::vk::CommandBufferUsageFlagBits::eOneTimeSubmit));
    recording_ = true;
  }
  return cmd_;
}

void Commands::submit_and_wait(std::string_view who, std::string_view remedy, ::vk::Semaphore wait,
                               ::vk::PipelineStageFlags wait_stage, ::vk::Semaphore signal) {
  if (!recording_) return;
  cmd_.end();
  recording_ = false;
  ::vk::CommandBuffer raw = *cmd_;
  ::vk::SubmitInfo info;
  info.setCommandBuffers(raw);
  if (wait) info.setWaitSemaphores(wait).setWaitDstStageMask(wait_stage);
  if (signal) info.setSignalSemaphores(signal);
  try {
    ctx_.queue().submit(info, *fence_);
    while (ctx_.device().waitForFences(*fence_, VK_TRUE, UINT64_MAX) == ::vk::Result::eTimeout) {
    }
  } catch (const ::vk::DeviceLostError&) {
    throw Error(std::string(who), "submit",
                fmt::format("device lost on {}", ctx_.caps().device_name), std::string(remedy));
  }
  ctx_.device().resetFences(*fence_);
}

}  // namespace masav::vk
