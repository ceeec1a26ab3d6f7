#pragma once
// The Vulkan compute backend: the kernel set as GLSL compute shaders, on any Vulkan 1.1 device.
#include <array>
#include <filesystem>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <string_view>

#include "compute/device/vk_context.h"
#include "compute/device/vk_memory.h"
#include "compute/push_padding.h"
#include "compute/sph_walk_choice.h"
#include "compute/vk_pipelines.h"
#include "compute/vk_stream.h"
#include "engine/kernels/backend.h"

namespace masav::vk {

// How radix_sort scatters each pass (VulkanTuning::sort_scatter; both portable: no workgroup
// waits on another): tiled, a workgroup sorts its tile in shared memory, then writes runs (GPUs);
// subgroup, one subgroup per workgroup ranks keys with ballots (CPU devices).
struct BackendOptions {
  ContextOptions context;
  Tuning tuning;                  // its `vulkan` part is this backend's (engine/core/tuning.h)
  bool count_loop_ticks = false;  // instrument every loop (tests of lavapipe's loop limit)
  std::filesystem::path cache_dir;  // the pipeline cache's directory; empty = no cache
  uint32_t workgroup_size = 256;
  uint32_t items_per_thread = 8;  // sort and scan tile = workgroup_size * items_per_thread
};

// The kernels the Vulkan backend runs in more than one dispatch, or with a shader chosen per call
// (run_own in vk_*.cpp); every other kernel is one dispatch of shaders/<name>.comp.
constexpr bool runs_own(KernelId k) {
  return k == KernelId::radix_sort || k == KernelId::grid_cell_ranges || k == KernelId::gather ||
         k == KernelId::grid_cell_offsets || k == KernelId::scatter_table ||
         k == KernelId::voxelize;
}

class VulkanBackend final : public Backend, public VulkanInterop {
 public:
  explicit VulkanBackend(const BackendOptions& options);
  ~VulkanBackend() override;

  const Capabilities& caps() const override { return ctx_.caps(); }
  std::unique_ptr<BufferImpl> create_buffer(ElemKind kind, size_t count,
                                            std::string_view label) override;
  void fill_u32(BufferImpl& dst, uint32_t value) override;
  void finish() override;
  TimestampId timestamp() override { return stream_.timestamp(); }
  double timestamp_ns(TimestampId id) override { return stream_.timestamp_ns(id); }
  void reset_timestamps() override { stream_.reset_timestamps(); }
  // Captured work replays a recording of the same commands (compute/vk_stream.h, "Replays"),
  // where replays_ (VulkanTuning::replay, on by default) allows.
  void begin_capture() override {
    if (replays_) stream_.begin_capture();
  }
  void end_capture() override { stream_.end_capture(); }
  void abort_capture() noexcept override { stream_.abort_capture(); }

  std::optional<uint32_t> take_max_loop_ticks() override;
  uint32_t tile_size() const { return options_.workgroup_size * options_.items_per_thread; }

  // For the renderer, which draws straight from the kernels' buffers on this device.
  const VulkanInterop* vulkan_interop() const override { return this; }
  const Context& vulkan_context() const override { return ctx_; }
  std::shared_ptr<Allocation> vulkan_buffer(const BufferImpl& b) const override {
    return alloc(b, "render");
  }
  SortScatter sort_scatter() const { return scatter_; }

 protected:
#include "engine/kernels/backend_overrides.inc"

  void write_bytes(BufferImpl& dst, const void* src, size_t bytes, size_t offset) override;
  void read_bytes(const BufferImpl& src, void* dst, size_t bytes, size_t offset) override;
  void copy_buffer(const BufferImpl& src, BufferImpl& dst, size_t bytes) override;
  // Asynchronous reads: a copy into the slot's host-visible buffer, submitted (Stream::flush),
  // and waited for by its submission's fence.
  void start_read(uint32_t slot, const BufferImpl& src, size_t bytes, size_t offset) override;
  bool end_read(uint32_t slot, void* dst, size_t bytes) override;

 private:
  const std::shared_ptr<Allocation>& alloc(const BufferImpl& b, std::string_view kernel) const;
  std::shared_ptr<Allocation> scratch(const std::string& slot, size_t bytes);
  // One pass of a multi-pass kernel; bit i of `written`: it writes buffers[i] (Stream::dispatch).
  // `push` is copied with its padding zeroed (compute/push_padding.h).
  template <class Push>
  void run(const KernelSpec& spec, std::initializer_list<std::shared_ptr<Allocation>> buffers,
           const Push* push, uint64_t groups, uint32_t written = ~0u) {
    const Push clean = without_padding(*push);
    run_bytes(spec, buffers, &clean, groups, written);
  }
  void run_bytes(const KernelSpec& spec, std::initializer_list<std::shared_ptr<Allocation>> buffers,
                 const void* push, uint64_t groups, uint32_t written);
  // One dispatch of shaders/<kernel>.comp over `items` invocations: `buffers` bound at 1..n in
  // the order of kernels.inc, each as its binding kind there says (compute/vk_bindings.h; a null
  // one, unused by the call, gets the first non-null one's memory), `push` the kernel's layout,
  // `written` the buffers it writes (bit i: buffers[i]), `constants` its variant
  // (compute/vk_variants.h). `extra` binds after them where the kernel has one (kernel_extra).
  void dispatch_kernel(KernelId kernel, std::span<const BufferImpl* const> buffers,
                       const void* push, uint32_t push_bytes, uint64_t items, uint32_t written,
                       SpecConstants constants, std::shared_ptr<Allocation> extra);
  // raymarch's first pass where ray_quads_ asks for it and the quads fit (vk_volume.cpp): the
  // volume's trilinear corners four to a texel (shaders/raymarch_quads.comp), made again only
  // when the volume or its contents changed; null where not used.
  std::shared_ptr<Allocation> raymarch_quads(const RaymarchLayout& layout,
                                             const BufferImpl& volume);
  // In-place exclusive prefix sum of data[0..count) for `kernel` (its scratch and its errors).
  void exclusive_scan(const std::shared_ptr<Allocation>& data, uint32_t count,
                      std::string_view kernel, uint32_t level = 0);
  void check_diagnostics();
  SortScatter choose_sort_scatter(SortScatter wanted) const;

  BackendOptions options_;
  Context ctx_;
  Pipelines pipelines_;
  Stream stream_;
  std::shared_ptr<Allocation> diag_;
  std::map<std::string, std::shared_ptr<Allocation>> scratch_;
  std::shared_ptr<Allocation> readback_;  // staging of downloads from device-only memory
  struct AsyncRead {
    std::shared_ptr<Allocation> staging;  // host-visible, grown as needed
    uint64_t serial = 0;                  // the submission that copies into it
  };
  std::array<AsyncRead, kMaxPendingReads> async_reads_;
  uint32_t pending_diag_limit_ = 0;  // the limit a pending diagnostic's message names
  SortScatter scatter_ = SortScatter::tiled;
  // The SPH neighbour rows walked by subgroup clusters (compute/sph_walk_choice.h).
  bool sph_coop_walk_ = true;
  // The SPH kernels that skip the wall images where no lane is near a wall
  // (compute/sph_walk_choice.h).
  SphWallSplit sph_wall_split_;
  // sph_forces adds the wall images after its masked walk (compute/sph_walk_choice.h).
  bool sph_images_after_ = false;
  // raymarch reads its volume four voxels to a texel (compute/raymarch_quads_choice.h).
  bool ray_quads_ = false;
  bool replays_ = true;
  std::shared_ptr<Allocation> quads_;  // raymarch_quads' output, of the volume below
  struct QuadSource {
    uint64_t serial = 0, writes = 0;  // the volume's Allocation::serial and ::writes
    uint32_t dims[3] = {0, 0, 0};
    bool operator==(const QuadSource&) const = default;
  } quads_of_;
};

}  // namespace masav::vk
