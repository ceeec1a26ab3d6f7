#pragma once
// One primary command buffer, recorded, submitted and waited for, again and again: what the
// compute backend's stream and the renderer both record into. The stream keeps a few of them
// so that it can record while earlier ones run (submit, then wait later).
#include <string_view>

#include "compute/device/vk_context.h"

namespace masav::vk {

class Commands {
 public:
  explicit Commands(const Context& ctx);
  ~Commands();  // waits for a submission still in flight
  Commands(const Commands&) = delete;
  Commands& operator=(const Commands&) = delete;

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
  // The two halves of submit_and_wait: submit ends and submits the recording (nothing when
  // nothing is recorded); wait waits for the last submission, if it has not been waited for.
  void submit(std::string_view who, std::string_view remedy, ::vk::Semaphore wait = {},
              ::vk::PipelineStageFlags wait_stage = {}, ::vk::Semaphore signal = {});
  void wait(std::string_view who, std::string_view remedy);
  bool in_flight() const { return in_flight_; }  // submitted and not yet waited for

 private:
  const Context& ctx_;
  ::vk::raii::CommandPool pool_ = nullptr;
  ::vk::raii::CommandBuffer cmd_ = nullptr;
  ::vk::raii::Fence fence_ = nullptr;
  bool recording_ = false;
  bool in_flight_ = false;
};

}  // namespace masav::vk
