#include "compute/vk_backend.h"

#include <fmt/format.h>

#include <cstdlib>
#include <cstring>

#include "compute/raymarch_quads_choice.h"
#include "compute/sph_walk_choice.h"
#include "compute/vk_bindings.h"
#include "engine/core/error.h"
#include "engine/core/limit_error.h"
#include "engine/kernels/kernel_checks.h"

namespace masav::vk {
namespace {

struct Diagnostics {
  uint32_t max_loop_ticks;
  uint32_t flags;
  uint32_t detail;
  uint32_t reserved;
};
constexpr Diagnostics kCleanDiagnostics{0, 0, UINT32_MAX, 0};

}  // namespace

SortScatter VulkanBackend::choose_sort_scatter(SortScatter wanted) const {
  // The subgroup scatter needs one fixed-size subgroup per workgroup and ballots.
  const bool fixed = ctx_.caps().min_subgroup_size == ctx_.caps().subgroup_size;
  const bool ballot = ctx_.subgroup_ballot();
  if (wanted == SortScatter::subgroup && !(fixed && ballot))
    throw Error("vulkan", "radix_sort",
                "the subgroup scatter needs a fixed subgroup size and "
                "subgroup ballots, which this device lacks",
                "use --tune vulkan.sort_scatter=tiled");
  if (wanted == SortScatter::automatic)
    wanted = ctx_.caps().device_type == "cpu" && fixed && ballot ? SortScatter::subgroup
                                                                 : SortScatter::tiled;
  return wanted;
}

bool sph_coop_walk(const VulkanTuning& t, std::string_view device_type) {
  return t.sph_walk == SphWalk::automatic ? device_type == "cpu"
                                          : t.sph_walk == SphWalk::cooperative;
}

SphWallSplit sph_wall_split(const VulkanTuning& t, std::string_view device_type) {
  return {resolve(t.sph_wall_split, true), resolve(t.sph_wall_split, device_type == "cpu")};
}

bool sph_images_after(const VulkanTuning& t, std::string_view device_type) {
  return resolve(t.sph_images_after, device_type != "cpu");
}

VulkanBackend::VulkanBackend(const BackendOptions& options)
    : options_(options),
      ctx_(options.context),
      pipelines_(ctx_, options.workgroup_size, options.count_loop_ticks, options.cache_dir,
                 counters_),
      stream_(ctx_, 4096, counters_) {
  if (tile_size() >= 65536)
    throw_invalid("vulkan", "workgroup_size * items_per_thread", std::to_string(tile_size()),
                  "below 65536 (the sort packs tile counts in 16 bits)");
  if (options.workgroup_size > ctx_.caps().max_workgroup_size || options.workgroup_size % 64)
    throw_invalid("vulkan", "workgroup_size", std::to_string(options.workgroup_size),
                  fmt::format("a multiple of 64 up to {}", ctx_.caps().max_workgroup_size));
  tuning_ = options.tuning;
  const VulkanTuning& t = options.tuning.vulkan;
  const std::string& type = ctx_.caps().device_type;
  scatter_ = choose_sort_scatter(t.sort_scatter);
  sph_coop_walk_ = sph_coop_walk(t, type);
  sph_wall_split_ = sph_wall_split(t, type);
  sph_images_after_ = sph_images_after(t, type);
  ray_quads_ = raymarch_quads_wanted(t, type);
  replays_ = resolve(t.replay, true);
  diag_ = allocate(ctx_, sizeof(Diagnostics), MemoryUse::readback, "diagnostics");
  std::memcpy(diag_->mapped, &kCleanDiagnostics, sizeof(Diagnostics));
}

VulkanBackend::~VulkanBackend() {
  try {
    stream_.submit_and_wait();
  } catch (...) {
  }
}

const std::shared_ptr<Allocation>& VulkanBackend::alloc(const BufferImpl& b,
                                                        std::string_view kernel) const {
  check_owner(*this, b, kernel);
  return static_cast<const VulkanBuffer&>(b).alloc();
}

std::unique_ptr<BufferImpl> VulkanBackend::create_buffer(ElemKind kind, size_t count,
                                                         std::string_view label) {
  check_fits(*this, kind, count, "create_buffer", fmt::format("buffer '{}'", label));
  const size_t bytes = count * elem_bytes(kind, real_bytes());
  return std::make_unique<VulkanBuffer>(
      this, kind, count, bytes, std::string(label),
      allocate(ctx_, bytes, MemoryUse::device, std::string(label)));
}

std::shared_ptr<Allocation> VulkanBackend::scratch(const std::string& slot, size_t bytes) {
  auto& a = scratch_[slot];
  if (!a || a->bytes < bytes) {
    if (ctx_.caps().max_buffer_bytes && bytes > ctx_.caps().max_buffer_bytes)
      throw LimitError("vulkan", slot,
                       fmt::format("scratch of {} MiB exceeds the {} MiB per buffer", bytes >> 20,
                                   ctx_.caps().max_buffer_bytes >> 20),
                       "use fewer elements", ctx_.caps().max_buffer_bytes);
    a = allocate(ctx_, bytes, MemoryUse::device, slot);  // the stream keeps the old one alive
  }
  return a;
}

void VulkanBackend::write_bytes(BufferImpl& dst, const void* src, size_t bytes, size_t offset) {
  stream_.end_capture();  // an upload is not captured (DeviceApi::begin_capture)
  const auto& a = alloc(dst, "upload");
  if (a->mapped) {
    stream_.submit_and_wait();  // earlier recorded work may still read the old contents
    std::memcpy(static_cast<uint8_t*>(a->mapped) + offset, src, bytes);
    ++a->writes;
    return;
  }
  auto staging = allocate(ctx_, bytes, MemoryUse::upload, "upload staging");
  std::memcpy(staging->mapped, src, bytes);
  stream_.copy(staging, 0, a, offset, bytes);
}

void VulkanBackend::read_bytes(const BufferImpl& src, void* dst, size_t bytes, size_t offset) {
  stream_.end_capture();
  const auto& a = alloc(src, "download");
  if (a->mapped) {
    finish();
    invalidate_for_host(ctx_, *a);
    std::memcpy(dst, static_cast<const uint8_t*>(a->mapped) + offset, bytes);
    return;
  }
  // One readback buffer, grown as needed and reused: the copy is waited for right here, so no
  // earlier download can still be using it (a per-step stats read allocates nothing).
  if (!readback_ || readback_->bytes < bytes)
    readback_ = allocate(ctx_, bytes, MemoryUse::readback, "download staging");
  stream_.copy(a, offset, readback_, 0, bytes);
  finish();
  invalidate_for_host(ctx_, *readback_);
  std::memcpy(dst, readback_->mapped, bytes);
}

void VulkanBackend::start_read(uint32_t slot, const BufferImpl& src, size_t bytes, size_t offset) {
  stream_.end_capture();
  AsyncRead& r = async_reads_[slot];
  // The slot is free: the read that last used its buffer was taken, so no copy still writes it.
  if (!r.staging || r.staging->bytes < bytes)
    r.staging = allocate(ctx_, bytes, MemoryUse::readback, "asynchronous read staging");
  stream_.copy(alloc(src, "asynchronous read"), offset, r.staging, 0, bytes);
  r.serial = stream_.flush();
}

bool VulkanBackend::end_read(uint32_t slot, void* dst, size_t bytes) {
  AsyncRead& r = async_reads_[slot];
  const bool later_work = stream_.wait_for(r.serial);
  invalidate_for_host(ctx_, *r.staging);
  std::memcpy(dst, r.staging->mapped, bytes);
  check_diagnostics();  // what the kernels up to the copy flagged
  return later_work;
}

void VulkanBackend::copy_buffer(const BufferImpl& src, BufferImpl& dst, size_t bytes) {
  stream_.copy(alloc(src, "copy"), 0, alloc(dst, "copy"), 0, bytes);
}

void VulkanBackend::fill_u32(BufferImpl& dst, uint32_t value) {
  stream_.fill(alloc(dst, "fill"), value);
}

void VulkanBackend::finish() {
  stream_.submit_and_wait();
  check_diagnostics();
}

void VulkanBackend::check_diagnostics() {
  auto* d = static_cast<Diagnostics*>(diag_->mapped);
  invalidate_for_host(ctx_, *diag_);
  if (d->flags == 0) return;
  const Diagnostics seen = *d;
  d->flags = 0;
  d->detail = UINT32_MAX;
  raise_diagnostics(*this, seen.flags, seen.detail, pending_diag_limit_);
}

std::optional<uint32_t> VulkanBackend::take_max_loop_ticks() {
  if (!options_.count_loop_ticks) return std::nullopt;
  finish();
  auto* d = static_cast<Diagnostics*>(diag_->mapped);
  const uint32_t ticks = d->max_loop_ticks;
  d->max_loop_ticks = 0;
  return ticks;
}

void VulkanBackend::run_bytes(const KernelSpec& spec,
                              std::initializer_list<std::shared_ptr<Allocation>> buffers,
                              const void* push, uint64_t groups, uint32_t written) {
  stream_.dispatch(pipelines_.get(spec), diag_,
                   std::span<const std::shared_ptr<Allocation>>(buffers.begin(), buffers.size()),
                   push, groups, written);
}

void VulkanBackend::dispatch_kernel(KernelId kernel, std::span<const BufferImpl* const> buffers,
                                    const void* push, uint32_t push_bytes, uint64_t items,
                                    uint32_t written, SpecConstants constants,
                                    std::shared_ptr<Allocation> extra) {
  const std::string_view name = kernel_name(kernel);
  if (bool(extra) != kernel_extra(kernel).has_value())
    throw Error("vulkan", std::string(name),
                "the binding after the kernel's buffers does not match "
                "kernel_extra (compute/vk_bindings.h)",
                "internal error: report it");
  const BufferImpl* any = nullptr;
  for (const BufferImpl* b : buffers) any = any ? any : b;
  std::vector<std::shared_ptr<Allocation>> allocs;
  for (const BufferImpl* b : buffers) allocs.push_back(alloc(b ? *b : *any, name));
  if (extra) allocs.push_back(std::move(extra));
  const uint32_t wg = options_.workgroup_size;
  const KernelSpec spec{name.data(), uint32_t(allocs.size()), push_bytes, std::move(constants),
                        0,           kernel_texels(kernel)};
  stream_.dispatch(pipelines_.get(spec), diag_, allocs, push, (items + wg - 1) / wg, written);
}

}  // namespace masav::vk
