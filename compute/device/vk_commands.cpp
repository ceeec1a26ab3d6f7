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

Commands::~Commands() {
  if (!in_flight_) return;
  // A lost device has nothing left to wait for; the buffer and fence go either way.
  try {
    (void)ctx_.device().waitForFences(*fence_, VK_TRUE, UINT64_MAX);
  } catch (...) {
  }
}

const ::vk::raii::CommandBuffer& Commands::begin() {
  if (!recording_) {
    wait("vulkan", "the GPU reset or a kernel faulted; restart masav");  // still running: finish it
    cmd_.reset();
    cmd_.begin(::vk::CommandBufferBeginInfo(::vk::CommandBufferUsageFlagBits::eOneTimeSubmit));
    recording_ = true;
  }
  return cmd_;
}

void Commands::submit_and_wait(std::string_view who, std::string_view remedy, ::vk::Semaphore wait,
                               ::vk::PipelineStageFlags wait_stage, ::vk::Semaphore signal) {
  submit(who, remedy, wait, wait_stage, signal);
  this->wait(who, remedy);
}

void Commands::submit(std::string_view who, std::string_view remedy, ::vk::Semaphore wait,
                      ::vk::PipelineStageFlags wait_stage, ::vk::Semaphore signal) {
  if (!recording_) return;  // recording: begin() waited for the last submission
  cmd_.end();
  recording_ = false;
  ::vk::CommandBuffer raw = *cmd_;
  ::vk::SubmitInfo info;
  info.setCommandBuffers(raw);
  if (wait) info.setWaitSemaphores(wait).setWaitDstStageMask(wait_stage);
  if (signal) info.setSignalSemaphores(signal);
  try {
    ctx_.queue().submit(info, *fence_);
  } catch (const ::vk::DeviceLostError&) {
    throw Error(std::string(who), "submit",
                fmt::format("device lost on {}", ctx_.caps().device_name), std::string(remedy));
  }
  in_flight_ = true;
}

void Commands::wait(std::string_view who, std::string_view remedy) {
  if (!in_flight_) return;
  in_flight_ = false;
  try {
    while (ctx_.device().waitForFences(*fence_, VK_TRUE, UINT64_MAX) == ::vk::Result::eTimeout) {
    }
  } catch (const ::vk::DeviceLostError&) {
    throw Error(std::string(who), "submit",
                fmt::format("device lost on {}", ctx_.caps().device_name), std::string(remedy));
  }
  ctx_.device().resetFences(*fence_);
}

}  // namespace masav::vk
