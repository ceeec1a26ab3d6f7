#pragma once
// Records dispatches, copies, fills and timestamps into a command buffer and submits it on
// finish (submit_and_wait), or without waiting (flush) so that the host records the next work
// while the device runs it: a ring of kInFlight command buffers, each with the allocations its
// commands touch kept alive until its fence is waited for. A memory barrier goes only where a
// command depends on one recorded since the last barrier (it reads or writes what was written, or
// writes what was read), so independent commands (the gathers of a grid rebuild) may overlap. A
// dispatch's descriptor set is cached by (kernel, buffers): a simulation binds the same few
// buffer combinations every step, so after the first step no set is allocated or written.
//
// Replays (DeviceApi::begin_capture): between begin_capture() and end_capture() the commands are
// only logged. end_capture() looks the log up among the last few recorded: the same commands
// (kernels, buffers, push constants, sizes) replay that recording, a secondary command buffer,
// with one vkCmdExecuteCommands; other ones are recorded into a new one first. The host then
// neither re-records a block of SPH steps nor orders, binds and pushes its dispatches one by one.
// What differs between blocks is dt: a captured sph_integrate takes it from a small table
// (capture_value) that the primary command buffer fills with vkCmdUpdateBuffer, in the command
// stream as push constants are, before it executes the recording.
#include <array>
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

  // ---- replays (see above). flush, submit_and_wait, wait_for and timestamp end a capture first.
  void begin_capture();
  void end_capture();
  void abort_capture() noexcept;  // drops what was logged
  bool capturing() const { return capturing_; }
  // The table entry a captured command reads `v` from (binding value_table()), filled before its
  // recording runs; kNoSlot when not capturing or the table is full (pass `v` inline then).
  static constexpr uint32_t kNoSlot = UINT32_MAX;
  uint32_t capture_value(float v);
  const std::shared_ptr<Allocation>& value_table() const { return value_table_; }
  static constexpr uint32_t kValueSlots = 1024;
  // A simulation's buffers rotate through a grid rebuild and a step with a period of three steps
  // and its blocks alternate two checkpoints: its full blocks come in up to six forms.
  static constexpr uint32_t kKeptRecordings = 12;

 private:
  static constexpr uint32_t kInFlight = 3;
  // One command as logged: a dispatch, a copy or a fill, with what it binds.
  struct Op {
    enum class Kind : uint8_t { dispatch, copy, fill } kind = Kind::dispatch;
    const Kernel* kernel = nullptr;
    // dispatch: diagnostics, then the kernel's buffers; copy: source, destination; fill: dst.
    std::vector<std::shared_ptr<Allocation>> bound;
    std::array<uint8_t, 128> push{};
    uint32_t push_bytes = 0;
    uint32_t gx = 0, gy = 0;
    uint32_t written = 0;  // dispatch: bit i, it writes bound[i + 1]
    ::vk::DeviceSize src_offset = 0, dst_offset = 0, bytes = 0;
    uint32_t value = 0;  // fill
  };
  // Logged commands recorded once into a secondary command buffer, replayed as long as kept.
  // It names its buffers by Allocation::serial only, never keeps them alive: a freed buffer's
  // serial never comes back, so a recording that binds one is never matched again (and ages
  // out); one that runs binds buffers that the log it matched holds.
  struct Recording {
    std::vector<Op> ops;            // the key, with `bound` empty
    std::vector<uint64_t> serials;  // of every op's bound buffers, in order
    ::vk::raii::CommandBuffer cmd = nullptr;
    uint64_t launches = 0, barriers = 0, fills = 0;
    bool matches(const std::vector<Op>& log) const;
  };
  struct Slot {
    std::vector<std::shared_ptr<Allocation>> alive;            // what its commands touch
    std::vector<std::shared_ptr<const Recording>> recordings;  // executed by its commands
    std::vector<std::vector<Op>> logs;  // theirs: the buffers they bind, kept alive
    uint64_t serial = 0;                // of its last submission
    std::unique_ptr<Commands> cmds;     // last: destroyed first, waiting for its submission
  };
  Commands& cmds() { return *ring_[current_].cmds; }
  // Where commands go: the secondary being recorded, else the slot's primary.
  const ::vk::raii::CommandBuffer& rec() { return target_ ? *target_ : cmds().cmd(); }
  void record(const Op& op);
  std::shared_ptr<const Recording> find_recording(const std::vector<Op>& ops);
  std::shared_ptr<const Recording> make_recording(const std::vector<Op>& log, bool& keep_it);
  void execute(const std::shared_ptr<const Recording>& r, std::vector<Op> log);
  void begin();
  bool any_in_flight() const;
  void retire(Slot& s);         // waits for its submission and releases what it kept alive
  void end_for_host();          // the barrier that makes the recorded writes visible to the host
  uint64_t submit_recording();  // submits the recording slot without waiting; its serial
  // A barrier before the next command when it depends on one since the last barrier.
  void order(std::span<const Allocation* const> reads, std::span<const Allocation* const> writes);
  void barrier();  // unconditionally (timestamps, the host)
  void record_barrier();
  void keep(const std::shared_ptr<Allocation>& a) {
    if (!target_) alive_.push_back(a);  // a recording's commands keep theirs (Recording::ops)
  }
  ::vk::DescriptorSet allocate_set(const Kernel& k);
  // The set binding `buffers` (diagnostics first) for `k`: cached, or written now.
  ::vk::DescriptorSet set_for(const Kernel& k,
                              std::span<const std::shared_ptr<Allocation>> buffers);

  // The kernel's set layout and the serials of the allocations bound (Allocation::serial), so a
  // key never matches a set written for buffers that were freed since.
  using SetKey = std::pair<VkDescriptorSetLayout, std::vector<uint64_t>>;

  const Context& ctx_;
  DeviceCounters& counters_;
  ::vk::raii::CommandPool recording_pool_ = nullptr;  // before ring_: its slots hold recordings
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
  std::vector<const Allocation*> read_, written_;           // since the last barrier
  std::vector<std::shared_ptr<Allocation>> alive_;          // of the recording
  std::vector<std::shared_ptr<const Recording>> executed_;  // by the recording
  std::vector<std::vector<Op>> executed_logs_;
  bool barrier_next_ = false;   // a recording ran: order the next command after all of it
  bool transient_set_ = false;  // set_for had to allocate a set outside the cache
  // Replays.
  bool capturing_ = false;
  std::vector<Op> log_;
  std::vector<float> values_;
  std::shared_ptr<Allocation> value_table_;
  const ::vk::raii::CommandBuffer* target_ = nullptr;
  std::vector<std::shared_ptr<const Recording>> recordings_;  // most recently used first
};

}  // namespace masav::vk
