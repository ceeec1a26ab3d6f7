#pragma once
// Records dispatches, copies, fills and timestamps into one command buffer and submits it on
// finish. A memory barrier goes only where a command depends on one recorded since the last
// barrier (it reads or writes what was written, or writes what was read), so independent
// commands (the gathers of a grid rebuild) may overlap. Every allocation a recorded
// command touches is kept alive until the fence signals. A dispatch's descriptor set is cached
// by (kernel, buffers): a simulation binds the same few buffer combinations every step, so after
// the first step no set is allocated or written.
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

  void submit_and_wait();
  // Device time of timestamp `id` in nanoseconds (after submit_and_wait).
  double timestamp_ns(uint32_t id);

 private:
  void begin();
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
  Commands cmds_;
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
  std::vector<const Allocation*> read_, written_;  // since the last barrier
  std::vector<std::shared_ptr<Allocation>> alive_;
};

}  // namespace masav::vk
