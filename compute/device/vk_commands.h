#pragma once
// One primary command buffer, recorded, submitted and waited for, again and again: what the
// compute backend's stream and the renderer both record into.
#include <string_view>

#include "compute/device/vk_context.h"

namespace masav::vk {

class Commands {
 public:
  explicit Commands(const Context& ctx);

  // The command buffer, begun (one-time submit) if it was not recording.
  const ::vk::raii::CommandBuffer& begin();
  bool recording() const { return recording_; }
  // The command buffer being recorded (after begin()).
  const ::vk::raii::CommandBuffer& cmd() const { return cmd_; }

  // Ends the recording, submits it (waiting on `wait` at `wait_stage`, signalling `signal`) and
  // waits for it; nothing when nothing is recorded. A lost device is an Error from `who` with
  // `remedy`.
  void submit_and_wait(std::string_view who, std::string_view remedy, ::vk::Semaphore wait = {},
                       ::vk::PipelineStageFlags wait_stage = {}, ::vk::Semaphore signal = {});

 private:
  const Context& ctx_;
  ::vk::raii::CommandPool pool_ = nullptr;
  ::vk::raii::CommandBuffer cmd_ = nullptr;
  ::vk::raii::Fence fence_ = nullptr;
  bool recording_ = false;
};

}  // namespace masav::vk
