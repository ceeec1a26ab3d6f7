#include "compute/vk_stream.h"

#include <fmt/format.h>

#include <algorithm>
#include <cstring>

#include "engine/core/error.h"

namespace masav::vk {
namespace {

constexpr uint32_t kSetsPerPool = 256;
constexpr uint32_t kBuffersPerSet = 16;
constexpr uint32_t kCachedSets = 1024;

::vk::raii::DescriptorPool make_pool(const Context& ctx, uint32_t sets) {
  const ::vk::DescriptorPoolSize sizes[] = {
      {::vk::DescriptorType::eStorageBuffer, sets * kBuffersPerSet},
      {::vk::DescriptorType::eUniformTexelBuffer, sets * kBuffersPerSet}};
  return ::vk::raii::DescriptorPool(ctx.device(), ::vk::DescriptorPoolCreateInfo({}, sets, sizes));
}

}  // namespace

Stream::Stream(const Context& ctx, uint32_t max_timestamps, DeviceCounters& counters)
    : ctx_(ctx), counters_(counters), max_timestamps_(max_timestamps) {
  recording_pool_ =
      ::vk::raii::CommandPool(ctx_.device(), ::vk::CommandPoolCreateInfo({}, ctx_.queue_family()));
  ring_.resize(kInFlight);
  for (Slot& s : ring_) s.cmds = std::make_unique<Commands>(ctx_);
  value_table_ = allocate(ctx_, kValueSlots * sizeof(float), MemoryUse::device, "replay values");
  queries_ = ::vk::raii::QueryPool(
      ctx_.device(), ::vk::QueryPoolCreateInfo({}, ::vk::QueryType::eTimestamp, max_timestamps_));
}

Stream::~Stream() {
  for (Slot& s : ring_) {
    try {
      retire(s);
    } catch (...) {  // a lost device: nothing left running
    }
  }
}

bool Stream::any_in_flight() const {
  for (const Slot& s : ring_)
    if (s.cmds->in_flight()) return true;
  return false;
}

void Stream::retire(Slot& s) {
  if (!s.cmds->in_flight()) return;
  s.cmds->wait("vulkan", "the GPU reset or a kernel faulted; restart masav, and report the scene");
  s.alive.clear();
  s.recordings.clear();
  s.logs.clear();
}

void Stream::begin() {
  if (cmds().recording()) return;
  Slot& slot = ring_[current_];
  if (slot.cmds->in_flight()) {
    // Every buffer of the ring is queued: wait for the oldest, this one.
    retire(slot);
    if (!any_in_flight()) ++counters_.host_syncs;
  }
  // Work still in flight may have written what the next commands read: the barrier rules of
  // order() carry over from it (submission order makes a barrier cover earlier buffers too).
  if (!any_in_flight()) {
    commands_recorded_ = false;
    barrier_next_ = false;
    read_.clear();
    written_.clear();
  }
  cmds().begin();
  if (queries_need_reset_) {
    cmds().cmd().resetQueryPool(*queries_, 0, max_timestamps_);
    queries_need_reset_ = false;
  }
}

void Stream::record_barrier() {
  using S = ::vk::PipelineStageFlagBits;
  using A = ::vk::AccessFlagBits;
  ::vk::MemoryBarrier mb(A::eShaderWrite | A::eTransferWrite,
                         A::eShaderRead | A::eShaderWrite | A::eTransferRead | A::eTransferWrite);
  rec().pipelineBarrier(S::eComputeShader | S::eTransfer, S::eComputeShader | S::eTransfer, {}, mb,
                        {}, {});
  ++counters_.barriers;
  read_.clear();
  written_.clear();
  barrier_next_ = false;
}

void Stream::barrier() {
  begin();
  if (commands_recorded_) record_barrier();
  commands_recorded_ = true;
}

void Stream::order(std::span<const Allocation* const> reads,
                   std::span<const Allocation* const> writes) {
  begin();
  auto in = [](const std::vector<const Allocation*>& set, const Allocation* a) {
    return std::find(set.begin(), set.end(), a) != set.end();
  };
  bool depends = false;
  for (const Allocation* r : reads) depends = depends || in(written_, r);
  for (const Allocation* w : writes) {
    depends = depends || in(written_, w) || in(read_, w);
    ++w->writes;
  }
  if ((depends || barrier_next_) && commands_recorded_) record_barrier();
  commands_recorded_ = true;
  read_.insert(read_.end(), reads.begin(), reads.end());
  written_.insert(written_.end(), writes.begin(), writes.end());
}

::vk::DescriptorSet Stream::allocate_set(const Kernel& k) {
  if (descriptor_pools_.empty() || sets_in_last_pool_ == kSetsPerPool) {
    descriptor_pools_.push_back(make_pool(ctx_, kSetsPerPool));
    sets_in_last_pool_ = 0;
  }
  ++sets_in_last_pool_;
  ::vk::DescriptorSetLayout layout = *k.set_layout;
  ::vk::DescriptorSetAllocateInfo info(*descriptor_pools_.back(), layout);
  // Plain handles: the pool is reset wholesale after the fence, which frees every set at once.
  return (*ctx_.device()).allocateDescriptorSets(info, *ctx_.device().getDispatcher()).front();
}

void Stream::dispatch(const Kernel& k, const std::shared_ptr<Allocation>& diag,
                      std::span<const std::shared_ptr<Allocation>> buffers, const void* push,
                      uint64_t groups, uint32_t written) {
  if (buffers.size() != k.buffers)
    throw Error("vulkan", k.name,
                fmt::format("{} buffers bound, kernel takes {}", buffers.size(), k.buffers),
                "internal error: report it");
  if (k.buffers + 1 > kBuffersPerSet)
    throw Error("vulkan", k.name, "too many buffers for one descriptor set", "internal error");
  if (k.push_bytes > sizeof(Op::push))
    throw Error("vulkan", k.name, "push constants beyond 128 bytes", "internal error");
  if (groups == 0) return;
  const uint64_t max_x = ctx_.caps().max_workgroups_x;
  const uint32_t gx = uint32_t(std::min<uint64_t>(groups, max_x));
  const uint64_t gy = (groups + gx - 1) / gx;
  if (gy > 65535)
    throw Error("vulkan", k.name, fmt::format("{} workgroups exceed this device's grid", groups),
                "use fewer elements");
  Op op;
  op.kind = Op::Kind::dispatch;
  op.kernel = &k;
  op.bound.reserve(buffers.size() + 1);
  op.bound.push_back(diag);
  op.bound.insert(op.bound.end(), buffers.begin(), buffers.end());
  op.push_bytes = k.push_bytes;
  if (k.push_bytes) std::memcpy(op.push.data(), push, k.push_bytes);
  op.gx = gx;
  op.gy = uint32_t(gy);
  op.written = written;
  if (capturing_)
    log_.push_back(std::move(op));
  else
    record(op);
}

void Stream::record(const Op& op) {
  std::vector<const Allocation*> reads, writes;
  switch (op.kind) {
    case Op::Kind::dispatch: {
      const Kernel& k = *op.kernel;
      // The diagnostics block (bound[0]) takes only atomics, in any order: not tracked.
      for (size_t i = 1; i < op.bound.size(); ++i)
        ((op.written >> (i - 1)) & 1u ? writes : reads).push_back(op.bound[i].get());
      order(reads, writes);
      for (const auto& b : op.bound) keep(b);
      const ::vk::DescriptorSet set = set_for(k, op.bound);
      rec().bindPipeline(::vk::PipelineBindPoint::eCompute, *k.pipeline);
      rec().bindDescriptorSets(::vk::PipelineBindPoint::eCompute, *k.layout, 0, set, {});
      if (op.push_bytes)
        rec().pushConstants<uint8_t>(
            *k.layout, ::vk::ShaderStageFlagBits::eCompute, 0,
            ::vk::ArrayProxy<const uint8_t>(op.push_bytes, op.push.data()));
      rec().dispatch(op.gx, op.gy, 1);
      ++counters_.launches;
      break;
    }
    case Op::Kind::copy: {
      const Allocation* read[] = {op.bound[0].get()};
      const Allocation* write[] = {op.bound[1].get()};
      order(read, write);
      rec().copyBuffer(*op.bound[0]->buffer, *op.bound[1]->buffer,
                       ::vk::BufferCopy(op.src_offset, op.dst_offset, op.bytes));
      keep(op.bound[0]);
      keep(op.bound[1]);
      break;
    }
    case Op::Kind::fill: {
      const Allocation* write[] = {op.bound[0].get()};
      order({}, write);
      rec().fillBuffer(*op.bound[0]->buffer, 0, VK_WHOLE_SIZE, op.value);
      keep(op.bound[0]);
      ++counters_.fills;
      break;
    }
  }
}

::vk::DescriptorSet Stream::set_for(const Kernel& k,
                                    std::span<const std::shared_ptr<Allocation>> buffers) {
  SetKey key{*k.set_layout, {}};
  key.second.reserve(buffers.size());
  for (const auto& b : buffers) key.second.push_back(b->serial);
  if (const auto it = set_cache_.find(key); it != set_cache_.end()) return it->second;
  ::vk::DescriptorSet set;
  const bool cacheable = cached_sets_ < kCachedSets;
  if (cacheable) {
    // Sets of the cache pool live until it is reset (only between submissions, below).
    if (!*cache_pool_) cache_pool_ = make_pool(ctx_, kCachedSets);
    ::vk::DescriptorSetLayout layout = *k.set_layout;
    set = (*ctx_.device())
              .allocateDescriptorSets(::vk::DescriptorSetAllocateInfo(*cache_pool_, layout),
                                      *ctx_.device().getDispatcher())
              .front();
    ++cached_sets_;
  } else {
    set = allocate_set(k);  // the cache is full until the next submission: a transient set
    transient_set_ = true;
  }
  std::vector<::vk::DescriptorBufferInfo> infos;
  std::vector<::vk::BufferView> views(buffers.size());
  infos.reserve(buffers.size());
  for (const auto& b : buffers) infos.emplace_back(*b->buffer, 0, VK_WHOLE_SIZE);
  std::vector<::vk::WriteDescriptorSet> writes;
  for (uint32_t i = 0; i < infos.size(); ++i) {
    const ::vk::DescriptorType type = descriptor_type(k, i);
    if (type == ::vk::DescriptorType::eUniformTexelBuffer) {
      const Texels& t = k.texels[i - 1];
      views[i] = texel_view(ctx_, *buffers[i], t.format, t.bytes, k.name);
      writes.emplace_back(set, i, 0, 1, type, nullptr, nullptr, &views[i]);
    } else {
      writes.emplace_back(set, i, 0, 1, type, nullptr, &infos[i]);
    }
  }
  ctx_.device().updateDescriptorSets(writes, {});
  if (cacheable) set_cache_.emplace(std::move(key), set);
  return set;
}

void Stream::copy(const std::shared_ptr<Allocation>& src, ::vk::DeviceSize src_offset,
                  const std::shared_ptr<Allocation>& dst, ::vk::DeviceSize dst_offset,
                  ::vk::DeviceSize bytes) {
  if (bytes == 0) return;
  Op op;
  op.kind = Op::Kind::copy;
  op.bound = {src, dst};
  op.src_offset = src_offset;
  op.dst_offset = dst_offset;
  op.bytes = bytes;
  if (capturing_)
    log_.push_back(std::move(op));
  else
    record(op);
}

void Stream::fill(const std::shared_ptr<Allocation>& dst, uint32_t value) {
  Op op;
  op.kind = Op::Kind::fill;
  op.bound = {dst};
  op.value = value;
  if (capturing_)
    log_.push_back(std::move(op));
  else
    record(op);
}

uint32_t Stream::timestamp() {
  end_capture();
  if (timestamps_used_ >= max_timestamps_)
    throw Error("vulkan", "timestamp", fmt::format("more than {} timestamps", max_timestamps_),
                "call reset_timestamps() between measurements");
  barrier();
  rec().writeTimestamp(::vk::PipelineStageFlagBits::eBottomOfPipe, *queries_, timestamps_used_);
  return timestamps_used_++;
}

void Stream::reset_timestamps() {
  timestamps_used_ = 0;
  queries_need_reset_ = true;
}

void Stream::end_for_host() {
  // Make device writes visible to the host's mapped reads after the fence.
  ::vk::MemoryBarrier to_host(
      ::vk::AccessFlagBits::eShaderWrite | ::vk::AccessFlagBits::eTransferWrite,
      ::vk::AccessFlagBits::eHostRead);
  cmds().cmd().pipelineBarrier(
      ::vk::PipelineStageFlagBits::eComputeShader | ::vk::PipelineStageFlagBits::eTransfer,
      ::vk::PipelineStageFlagBits::eHost, {}, to_host, {}, {});
}

uint64_t Stream::submit_recording() {
  end_for_host();
  Slot& slot = ring_[current_];
  slot.cmds->submit("vulkan",
                    "the GPU reset or a kernel faulted; restart masav, and report the scene");
  slot.serial = ++last_serial_;
  slot.alive = std::move(alive_);
  alive_.clear();
  slot.recordings = std::move(executed_);
  executed_.clear();
  slot.logs = std::move(executed_logs_);
  executed_logs_.clear();
  current_ = (current_ + 1) % kInFlight;
  return slot.serial;
}

uint64_t Stream::flush() {
  end_capture();
  if (!cmds().recording()) return last_serial_;
  // Transient descriptor sets (the cache was full) are freed only when the device is idle.
  if (sets_in_last_pool_ > 0 || descriptor_pools_.size() > 1 || cached_sets_ >= kCachedSets) {
    submit_and_wait();
    return last_serial_;
  }
  return submit_recording();
}

bool Stream::wait_for(uint64_t serial) {
  end_capture();
  bool waited = false;
  for (Slot& s : ring_) {
    if (s.cmds->in_flight() && s.serial <= serial) {
      retire(s);
      waited = true;
    }
  }
  const bool later = any_in_flight();
  if (waited && !later) ++counters_.host_syncs;
  return later;
}

void Stream::submit_and_wait() {
  end_capture();
  if (!cmds().recording() && !any_in_flight()) return;
  if (cmds().recording()) submit_recording();
  for (Slot& s : ring_) retire(s);
  ++counters_.host_syncs;
  for (auto& p : descriptor_pools_) p.reset();
  if (descriptor_pools_.size() > 1)
    descriptor_pools_.erase(descriptor_pools_.begin() + 1, descriptor_pools_.end());
  sets_in_last_pool_ = 0;
  read_.clear();
  written_.clear();
  barrier_next_ = false;
  if (cached_sets_ >= kCachedSets) {
    // Full: start over (no recorded work uses a set any more; the recordings bind them).
    recordings_.clear();
    set_cache_.clear();
    cache_pool_.reset();
    cached_sets_ = 0;
  }
}

double Stream::timestamp_ns(uint32_t id) {
  if (id >= timestamps_used_)
    throw Error("vulkan", "timestamp", fmt::format("no timestamp {}", id),
                "use an id returned by timestamp() since the last reset");
  const auto [result, ticks] = queries_.getResult<uint64_t>(
      id, 1, sizeof(uint64_t), ::vk::QueryResultFlagBits::e64 | ::vk::QueryResultFlagBits::eWait);
  (void)result;
  const uint32_t bits = ctx_.timestamp_valid_bits();
  const uint64_t mask = bits >= 64 ? ~0ull : ((1ull << bits) - 1);
  return double(ticks & mask) * ctx_.caps().timestamp_period_ns;
}

}  // namespace masav::vk
