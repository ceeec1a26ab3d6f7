#pragma once
// The CUDA backend (host side, plain C++): memory, stream, events and checks. The kernels live
// in *_kernels.cu and call the shared MASAV_HD math (the code the CPU reference runs). Every
// launch, copy and memset is queued on one non-blocking stream; the host waits for it only where
// it needs data (downloads, finish()), and finish() also reads the kernels' diagnostics.
#include <cuda_runtime_api.h>

#include <array>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "engine/kernels/backend.h"

namespace masav::cuda {

class CudaBuffer final : public BufferImpl {
 public:
  CudaBuffer(const DeviceApi* owner, ElemKind kind, size_t count, size_t bytes, std::string label,
             void* ptr)
      : BufferImpl(owner, kind, count, bytes, std::move(label)), ptr_(ptr) {}
  ~CudaBuffer() override;
  void* ptr() const { return ptr_; }

 private:
  void* ptr_;
};

// Device scratch memory, freed on destruction; CudaBackend::scratch grows it.
struct DeviceScratch {
  void* ptr = nullptr;
  size_t bytes = 0;
  ~DeviceScratch();
};

class CudaBackend final : public Backend {
 public:
  explicit CudaBackend(int device, const Tuning& tuning = {});
  ~CudaBackend() override;

  const Capabilities& caps() const override { return caps_; }
  std::unique_ptr<BufferImpl> create_buffer(ElemKind kind, size_t count,
                                            std::string_view label) override;
  void fill_u32(BufferImpl& dst, uint32_t value) override;
  void finish() override;
  TimestampId timestamp() override;
  double timestamp_ns(TimestampId id) override;
  void reset_timestamps() override;
  // A capture is a CUDA graph of the stream's work, with CudaTuning::graphs on (and not with
  // sync_each_launch); otherwise nothing. Each capture updates one of two executable graphs
  // kept, in turn (same shape: new parameters such as dt) or, where its shape differs, replaces
  // it (cuda_capture.cpp).
  void begin_capture() override;
  void end_capture() override;
  void abort_capture() noexcept override;

  cudaStream_t stream() const { return stream_; }
  uint32_t* diagnostics() const { return diag_; }  // {max_loop_ticks, flags, detail, reserved}
  dim3 grid_for(uint64_t blocks, const char* kernel) const;
  dim3 grid_for_items(uint64_t items, const char* kernel) const;

 protected:
#include "engine/kernels/backend_overrides.inc"

  void write_bytes(BufferImpl& dst, const void* src, size_t bytes, size_t offset) override;
  void read_bytes(const BufferImpl& src, void* dst, size_t bytes, size_t offset) override;
  void copy_buffer(const BufferImpl& src, BufferImpl& dst, size_t bytes) override;
  // Asynchronous reads: the bytes and the diagnostics words copied into the slot's pinned host
  // memory on the stream, then an event; end_read waits for that event alone.
  void start_read(uint32_t slot, const BufferImpl& src, size_t bytes, size_t offset) override;
  bool end_read(uint32_t slot, void* dst, size_t bytes) override;

 private:
  void* ptr(const BufferImpl& b, const char* kernel) const;
  // The device address of a buffer, as the element type the kernel reads (float4 -> hd::V4).
  template <class T, class E>
  T* device_ptr(const Buffer<E>& b, const char* kernel) const {
    return static_cast<T*>(ptr(b.impl(), kernel));
  }
  // Every launch ends here: checks and counts it and remembers it, so that a fault CUDA reports
  // later can name it; with sync_each_launch it also waits for the kernel, so a fault names its
  // kernel exactly. `step`: the kernel's pass within a multi-launch run, or null.
  void launched(cudaError_t status, const char* kernel, const char* step = nullptr);
  // Checks a call on the stream, where a fault of an earlier kernel may surface.
  void check_stream(cudaError_t status, const char* where, const char* what) const;
  std::string last_launch() const;
  void wait(const char* where);  // the host blocks until the stream has run dry
  // Waits for the stream and raises what the kernels flagged in the diagnostics words.
  void settle(const char* where);
  void clear_diagnostics(const char* where);
  // Stream-ordered, counted memsets (to zero, to `byte`) and device-to-device copy.
  void zero(void* dst, size_t bytes, const char* kernel);
  void set_bytes(void* dst, int byte, size_t bytes, const char* kernel);
  void copy_device(void* dst, const void* src, size_t bytes, const char* kernel);
  // Scratch memory `name` of at least `bytes`. Growing it frees the old block, which waits for
  // the whole device (cudaFree); a scene's sizes settle after its first step.
  void* scratch(const std::string& name, size_t bytes, const char* kernel);
  void sort_portable(uint32_t n, uint32_t key_bits, uint32_t* keys, uint32_t* values);
  void sort_cub(uint32_t n, uint32_t key_bits, uint32_t* keys, uint32_t* values);
  // In-place exclusive prefix sum of data[0..count) for `kernel` (its scratch and its errors).
  void exclusive_scan(uint32_t* data, uint32_t count, const char* kernel, uint32_t level = 0);

  int device_;
  Capabilities caps_;
  cudaStream_t stream_ = nullptr;
  uint32_t* diag_ = nullptr;
  std::vector<cudaEvent_t> events_;
  uint32_t events_used_ = 0;
  uint32_t pending_diag_limit_ = 0;
  std::map<std::string, DeviceScratch> scratch_;
  struct AsyncRead {
    void* pinned = nullptr;  // cudaMallocHost: the bytes, then the diagnostics words
    size_t bytes = 0;        // room for the bytes
    cudaEvent_t done = nullptr;
    uint64_t work_mark = 0;  // the stream's work count when the read was queued
  };
  std::array<AsyncRead, kMaxPendingReads> async_reads_;
  // Launches, fills and copies queued so far: whether work followed a read (end_read).
  uint64_t work_count() const;
  // Ends a capture in progress and launches its graph; every call that cannot be captured
  // (allocations, host copies, waits, events) calls it first.
  void leave_capture();
  bool sync_each_launch_ = false;  // CudaTuning::sync_each_launch
  bool graphs_ = false;            // captures made (CudaTuning::graphs, not with the sync)
  bool sph_images_after_ = true;   // sph_forces' wall images after its walk (CudaTuning)
  bool capturing_ = false;
  std::array<cudaGraphExec_t, 2> graph_execs_{};
  uint32_t next_graph_exec_ = 0;
  const char* last_kernel_ = nullptr;  // the last launch (static strings), for fault messages
  const char* last_step_ = nullptr;
};

}  // namespace masav::cuda
