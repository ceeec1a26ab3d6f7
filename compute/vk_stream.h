#pragma once
// Records dispatches, copies, fills and timestamps into a command buffer and submits it on
// finish (submit_and_wait), or without waiting (flush) so that the host records the next work
// while the device runs it: a ring of kInFlight command buffers, each with the allocations its
// commands touch kept alive until its fence is waited for. A memory barrier goes only where a
// command depends on one recorded since the last barrier (it reads or writes what was written, or
// writes what was read), so independent commands (the gathers of a grid rebuild) may overlap. A
// dispatch's descriptor set is cached by (kernel, buffers): a simulation binds the same few
// buffer combinations every step, so after the first step no set is allocated or written.
#include <map>
#include <memory>
#include <span>
#include <vector>

#include "compute/device/vk_commands.h"
#include "compute/device/vk_memory.h"
#include "compute/vk_pipelines.h"
#include "engine/core/device_api.h"

namespace masav::vk {

class Stream {
 public:
  // Counts dispatches, barriers, fills and host waits into `counters` (the backend's).
  Stream(const Context& ctx, uint32_t max_timestamps, DeviceCounters& counters);
  ~Stream();  // waits for what is in flight before its pools and allocations go
  Stream(const Stream&) = delete;
  Stream& operator=(const Stream&) = delete;

  // Binds `diag` at binding 0 and `buffers` at 1..n; groups beyond maxComputeWorkGroupCount[0]
  // spill into y (kernels flatten them with flat_group_id()). Bit i of `written` says the kernel
  // writes buffers[i] (the others it only reads); the diagnostics block takes only atomics, in
  // any order, and is not tracked.
  void dispatch(const Kernel& k, const std::shared_ptr<Allocation>& diag,
                std::span<const std::shared_ptr<Allocation>> buffers, const void* push,
                uint64_t groups, uint32_t written = ~0u);
  void copy(const std::shared_ptr<Allocation>& src, ::vk::DeviceSize src_offset,
            const std::shared_ptr<Allocation>& dst, ::vk::DeviceSize dst_offset,
            ::vk::DeviceSize bytes);
  void fill(const std::shared_ptr<Allocation>& dst, uint32_t value);
  uint32_t timestamp();
  void reset_timestamps();

  // Submits everything and waits for all of it (one host sync).
  void submit_and_wait();
  // Submits what is recorded without waiting and returns its serial (the last serial when
  // nothing is recorded). wait_for(serial) waits for that submission and those before it still
  // in flight, and returns whether later work is still queued (a wait that leaves nothing
  // queued drained the device: a host sync).
  uint64_t flush();
  bool wait_for(uint64_t serial);
  // Device time of timestamp `id` in nanoseconds (after submit_and_wait).
  double timestamp_ns(uint32_t id);

 private:
  static constexpr uint32_t kInFlight = 3;
  struct Slot {
    std::vector<std::shared_ptr<Allocation>> alive;  // what its commands touch
    uint64_t serial = 0;                             // of its last submission
    std::unique_ptr<Commands> cmds;  // last: destroyed first, waiting for its submission
  };
  Commands& cmds() { return *ring_[current_].cmds; }
  void begin();
  bool any_in_flight() const;
  void retire(Slot& s);         // waits for its submission and releases what it kept alive
  void end_for_host();          // the barrier that makes the recorded writes visible to the host
  uint64_t submit_recording();  // submits the recording slot without waiting; its serial
  // A barrier before the next command when it depends on one since the last barrier.
  void order(std::span<const Allocation* const> reads, std::span<const Allocation* const> writes);
  void barrier();  // unconditionally (timestamps, the host)
  void record_barrier();
  void keep(const std::shared_ptr<Allocation>& a) { alive_.push_back(a); }
  ::vk::DescriptorSet allocate_set(const Kernel& k);
  // The set binding `buffers` (diagnostics first) for `k`: cached, or written now.
  ::vk::DescriptorSet set_for(const Kernel& k,
                              std::span<const std::shared_ptr<Allocation>> buffers);

  // The kernel's set layout and the serials of the allocations bound (Allocation::serial), so a
  // key never matches a set written for buffers that were freed since.
  using SetKey = std::pair<VkDescriptorSetLayout, std::vector<uint64_t>>;

  const Context& ctx_;
  DeviceCounters& counters_;
  std::vector<Slot> ring_;
  uint32_t current_ = 0;  // the slot recording now
  uint64_t last_serial_ = 0;
  ::vk::raii::QueryPool queries_ = nullptr;
  std::vector<::vk::raii::DescriptorPool> descriptor_pools_;
  uint32_t sets_in_last_pool_ = 0;
  ::vk::raii::DescriptorPool cache_pool_ = nullptr;  // the cached sets; reset when full
  uint32_t cached_sets_ = 0;
  std::map<SetKey, ::vk::DescriptorSet> set_cache_;
  uint32_t max_timestamps_;
  uint32_t timestamps_used_ = 0;
  bool queries_need_reset_ = true;
  bool commands_recorded_ = false;
  std::vector<const Allocation*> read_, written_;   // since the last barrier
  std::vector<std::shared_ptr<Allocation>> alive_;  // of the recording
};

}  // namespace masav::vk
