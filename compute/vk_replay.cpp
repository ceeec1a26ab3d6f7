// Stream's replays (compute/vk_stream.h, "Replays"): a captured block of commands is logged,
// looked up among the recordings kept, and recorded into a secondary command buffer only when
// none has the same commands.
#include <cstring>

#include "compute/vk_stream.h"

namespace masav::vk {

bool Stream::Recording::matches(const std::vector<Op>& log) const {
  if (log.size() != ops.size()) return false;
  size_t s = 0;
  for (size_t i = 0; i < log.size(); ++i) {
    const Op &k = ops[i], &o = log[i];
    if (k.kind != o.kind || k.kernel != o.kernel || k.push_bytes != o.push_bytes || k.gx != o.gx ||
        k.gy != o.gy || k.written != o.written || k.src_offset != o.src_offset ||
        k.dst_offset != o.dst_offset || k.bytes != o.bytes || k.value != o.value)
      return false;
    if (k.push_bytes && std::memcmp(k.push.data(), o.push.data(), k.push_bytes) != 0) return false;
    for (const auto& b : o.bound)
      if (s >= serials.size() || serials[s++] != b->serial) return false;
  }
  return s == serials.size();
}

void Stream::begin_capture() {
  if (capturing_) return;
  capturing_ = true;
  log_.clear();
  values_.clear();
}

void Stream::abort_capture() noexcept {
  capturing_ = false;
  log_.clear();
  values_.clear();
}

uint32_t Stream::capture_value(float v) {
  if (!capturing_ || values_.size() >= kValueSlots) return kNoSlot;
  values_.push_back(v);
  return uint32_t(values_.size() - 1);
}

void Stream::end_capture() {
  if (!capturing_) return;
  capturing_ = false;
  std::vector<Op> log = std::move(log_);
  log_.clear();
  if (log.empty()) {
    values_.clear();
    return;
  }
  std::shared_ptr<const Recording> r = find_recording(log);
  if (!r) {
    bool keep_it = false;
    r = make_recording(log, keep_it);
    ++counters_.graph_builds;
    if (keep_it) {
      if (recordings_.size() >= kKeptRecordings) recordings_.pop_back();
      recordings_.insert(recordings_.begin(), r);
    }
  }
  execute(r, std::move(log));
  values_.clear();
}

std::shared_ptr<const Stream::Recording> Stream::find_recording(const std::vector<Op>& log) {
  for (size_t i = 0; i < recordings_.size(); ++i) {
    if (!recordings_[i]->matches(log)) continue;
    std::shared_ptr<const Recording> r = recordings_[i];
    recordings_.erase(recordings_.begin() + ptrdiff_t(i));
    recordings_.insert(recordings_.begin(), r);
    return r;
  }
  return nullptr;
}

std::shared_ptr<const Stream::Recording> Stream::make_recording(const std::vector<Op>& log,
                                                                bool& keep_it) {
  auto r = std::make_shared<Recording>();
  ::vk::raii::CommandBuffers bufs(
      ctx_.device(),
      ::vk::CommandBufferAllocateInfo(*recording_pool_, ::vk::CommandBufferLevel::eSecondary, 1));
  r->cmd = std::move(bufs.front());
  const ::vk::CommandBufferInheritanceInfo inherit;
  // Simultaneous use: the ring may hold several submissions that execute it.
  r->cmd.begin(
      ::vk::CommandBufferBeginInfo(::vk::CommandBufferUsageFlagBits::eSimultaneousUse, &inherit));
  begin();  // the primary, before the order state is set aside for the recording
  // The recording starts after a barrier (execute): nothing before it is pending within it.
  std::vector<const Allocation*> read = std::move(read_), written = std::move(written_);
  read_.clear();
  written_.clear();
  const bool recorded = commands_recorded_, barrier_next = barrier_next_;
  commands_recorded_ = false;
  barrier_next_ = false;
  const DeviceCounters before = counters_;
  transient_set_ = false;
  auto restore = [&] {
    target_ = nullptr;
    read_ = std::move(read);
    written_ = std::move(written);
    commands_recorded_ = recorded;
    barrier_next_ = barrier_next;
    // execute() counts the recording's commands each time it runs them.
    r->launches = counters_.launches - before.launches;
    r->barriers = counters_.barriers - before.barriers;
    r->fills = counters_.fills - before.fills;
    counters_.launches = before.launches;
    counters_.barriers = before.barriers;
    counters_.fills = before.fills;
  };
  target_ = &r->cmd;
  try {
    for (const Op& op : log) record(op);
    r->cmd.end();
  } catch (...) {
    restore();
    throw;
  }
  restore();
  r->ops.reserve(log.size());
  for (const Op& op : log) {
    for (const auto& b : op.bound) r->serials.push_back(b->serial);
    Op key = op;
    key.bound.clear();
    r->ops.push_back(std::move(key));
  }
  // A transient set is freed at the next wait for the device: such a recording runs once.
  keep_it = !transient_set_;
  return r;
}

void Stream::execute(const std::shared_ptr<const Recording>& r, std::vector<Op> log) {
  begin();
  // What was recorded before it is done before it starts (its commands were ordered among
  // themselves only), and so is the previous replay's read of the values.
  if (commands_recorded_) record_barrier();
  if (!values_.empty()) {
    cmds().cmd().updateBuffer<float>(
        *value_table_->buffer, 0,
        ::vk::ArrayProxy<const float>(uint32_t(values_.size()), values_.data()));
    record_barrier();
  }
  cmds().cmd().executeCommands(*r->cmd);
  commands_recorded_ = true;
  barrier_next_ = true;  // whatever comes next may depend on any of its commands
  counters_.launches += r->launches;
  counters_.barriers += r->barriers;
  counters_.fills += r->fills;
  ++counters_.graphs;
  // Allocation::writes: one more for each command that writes the buffer.
  for (const Op& op : log) {
    if (op.kind == Op::Kind::dispatch) {
      for (size_t i = 1; i < op.bound.size(); ++i)
        if ((op.written >> (i - 1)) & 1u) ++op.bound[i]->writes;
    } else {
      ++op.bound.back()->writes;  // a copy's destination, a fill's buffer
    }
  }
  executed_.push_back(r);
  executed_logs_.push_back(std::move(log));  // keeps its buffers alive while it runs
}

}  // namespace masav::vk
