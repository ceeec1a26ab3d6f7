#pragma once
// Buffers, ordering and device timestamps: what every backend provides besides its kernels
// (the kernels are listed in backend.h). Work is recorded in order; downloads wait for it.
#include <array>
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "engine/core/buffer.h"
#include "engine/core/capabilities.h"

namespace masav {

using TimestampId = uint32_t;

// What a backend asked of the device since the last reset_counters(): `masav bench sph` reports
// them per step, so a pipeline that syncs, copies or launches more than it should shows it.
// Byte counts are kept here for every backend; the rest by each backend where it does the work.
struct DeviceCounters {
  uint64_t launches = 0;         // kernel launches (CUDA) / dispatches (Vulkan) / kernel runs (CPU)
  uint64_t barriers = 0;         // pipeline barriers recorded (Vulkan)
  uint64_t host_syncs = 0;       // times the host blocked until the device finished its work
  uint64_t fills = 0;            // buffer fills / memsets
  uint64_t device_copies = 0;    // device-to-device copies
  uint64_t bytes_to_device = 0;  // host -> device (uploads)
  uint64_t bytes_to_host = 0;    // device -> host (downloads, including asynchronous reads)
  uint64_t async_reads = 0;      // reads taken while the device still had later work to run
  // Captured work queued as one unit (DeviceApi::begin_capture): CUDA graph launches, Vulkan
  // executions of a recorded command buffer. graph_builds: those that first built their unit
  // (CUDA: instantiated a graph; Vulkan: recorded the commands); the others reused one.
  uint64_t graphs = 0;
  uint64_t graph_builds = 0;
  // Kernel forms compiled while running (Vulkan: pipelines created, each form's first use on
  // this backend; a driver compile unless its pipeline cache holds it, ~0.1 s on lavapipe). CUDA
  // and the CPU reference compile every kernel ahead of time: none. A step that builds one
  // stalls the host, so a steady run should count none.
  uint64_t pipelines_built = 0;
};

class DeviceApi;

// begin_capture() on construction; end_capture() on commit(), abort_capture() when it goes out
// of scope uncommitted (an exception on the way).
class CaptureScope {
 public:
  explicit CaptureScope(DeviceApi& d);
  ~CaptureScope();
  CaptureScope(const CaptureScope&) = delete;
  CaptureScope& operator=(const CaptureScope&) = delete;
  void commit();

 private:
  DeviceApi& d_;
  bool open_ = true;
};

class DeviceApi {
 public:
  virtual ~DeviceApi() = default;

  virtual const Capabilities& caps() const = 0;
  const std::string& name() const { return caps().backend; }
  size_t real_bytes() const { return caps().real_is_double ? 8 : 4; }

  // ---- buffers (ordered with the kernels recorded before them)
  template <class T>
  Buffer<T> create(size_t count, std::string_view label) {
    return Buffer<T>(create_buffer(elem_kind_of<T>(), count, label));
  }
  virtual std::unique_ptr<BufferImpl> create_buffer(ElemKind kind, size_t count,
                                                    std::string_view label) = 0;
  // Byte-level access, bounds- and owner-checked here for every backend.
  void upload_bytes(BufferImpl& dst, const void* src, size_t bytes, size_t offset);
  void download_bytes(const BufferImpl& src, void* dst, size_t bytes, size_t offset);
  void copy_bytes(const BufferImpl& src, BufferImpl& dst, size_t bytes);
  virtual void fill_u32(BufferImpl& dst, uint32_t value) = 0;

  // ---- asynchronous reads
  // read_async queues a copy of `bytes` of `src` (from `offset`) behind the work recorded so far,
  // submits that work without waiting for it, and returns a ticket. take_read(ticket) waits for
  // that copy alone -- work recorded after it keeps the device busy meanwhile -- and returns the
  // bytes as they were when the copy ran. Each ticket is taken once, in any order; at most
  // kMaxPendingReads are outstanding. A take with later work still queued counts as an
  // asynchronous read; one that waits and leaves nothing queued, as a host sync.
  static constexpr uint32_t kMaxPendingReads = 16;
  uint64_t read_async(const BufferImpl& src, size_t bytes, size_t offset = 0);
  std::vector<uint8_t> take_read(uint64_t ticket);
  // Takes a read nobody needs (a block rolled back, an error on the way); 0 is no read. A device
  // error here is left to the call that reports errors.
  void discard_read(uint64_t ticket) noexcept;
  // Whole buffers the same way, converted as download() converts them: several reads queued
  // together and then taken cost one wait, where one download() each would cost one wait each.
  template <class T>
  uint64_t read_async(const Buffer<T>& b) {
    return read_async(b.impl(), b.impl().bytes());
  }
  std::vector<uint32_t> take_u32s(uint64_t ticket);
  std::vector<double> take_reals(uint64_t ticket);  // a Buffer<Real>
  std::vector<Vec4d> take_real4s(uint64_t ticket);  // a Buffer<Real4>

  // ---- work queued as one unit
  // Between begin_capture() and end_capture() a backend may gather what is recorded and queue it
  // as one unit: CUDA captures it as a graph, so the device runs the kernels back to back
  // instead of the host launching each; Vulkan replays a recording of the same commands made
  // before, so the host records and orders nothing (compute/vk_stream.h, "Replays").
  // Results and order are the same as without. A call that cannot be captured (an allocation,
  // an upload or download, a wait, a timestamp) ends the capture first: what was captured is
  // queued then, the rest as usual. abort_capture() drops what was captured and not yet queued:
  // only on the way out of an error, when that work is abandoned anyway. CaptureScope pairs them.
  virtual void begin_capture() {}
  virtual void end_capture() {}
  virtual void abort_capture() noexcept {}

  // ---- ordering and timing
  virtual void finish() = 0;            // submit what is recorded and wait for it
  virtual TimestampId timestamp() = 0;  // records a device timestamp after the work so far
  virtual double timestamp_ns(TimestampId id) = 0;  // valid after finish()
  virtual void reset_timestamps() = 0;

  const DeviceCounters& counters() const { return counters_; }
  void reset_counters() { counters_ = {}; }

  // ---- typed helpers (convert Real/Real4 to the backend's precision)
  void upload(Buffer<uint32_t>& b, std::span<const uint32_t> v);
  void upload(Buffer<int32_t>& b, std::span<const int32_t> v);
  void upload(Buffer<float>& b, std::span<const float> v);
  void upload(Buffer<Real>& b, std::span<const double> v);
  void upload(Buffer<Real>& b, std::span<const float> v);
  void upload(Buffer<Real4>& b, std::span<const Vec4d> v);
  void upload(Buffer<Real4>& b, std::span<const Vec4f> v);
  std::vector<uint32_t> download(const Buffer<uint32_t>& b);
  std::vector<int32_t> download(const Buffer<int32_t>& b);
  std::vector<float> download(const Buffer<float>& b);
  std::vector<double> download(const Buffer<Real>& b);
  std::vector<Vec4d> download(const Buffer<Real4>& b);
  // Positions exactly as a GPU backend stores them (rounded to fp32 on the CPU reference).
  std::vector<Vec4f> download_f32(const Buffer<Real4>& b);

  template <class T>
  void copy(const Buffer<T>& src, Buffer<T>& dst) {
    copy_bytes(src.impl(), dst.impl(), src.impl().bytes());
  }
  template <class T>
  void fill(Buffer<T>& dst, uint32_t word) {
    fill_u32(dst.impl(), word);
  }

 protected:
  // The backends' byte copies; arguments are already checked (in range, owned, bytes > 0).
  virtual void write_bytes(BufferImpl& dst, const void* src, size_t bytes, size_t offset) = 0;
  virtual void read_bytes(const BufferImpl& src, void* dst, size_t bytes, size_t offset) = 0;
  virtual void copy_buffer(const BufferImpl& src, BufferImpl& dst, size_t bytes) = 0;

  // A backend's side of read_async / take_read, in slot `slot` (< kMaxPendingReads, free until
  // end_read returns). end_read returns whether later work is still queued. The defaults
  // read at start_read (a backend whose work is done when it is recorded: the CPU reference).
  virtual void start_read(uint32_t slot, const BufferImpl& src, size_t bytes, size_t offset);
  virtual bool end_read(uint32_t slot, void* dst, size_t bytes);

  void check_upload(const BufferImpl& dst, size_t count) const;
  // `b` is this backend's and [offset, offset + bytes) lies in it (`what`: upload, download).
  void check_range(const BufferImpl& b, size_t bytes, size_t offset, const char* what) const;
  void upload_reals(BufferImpl& dst, const double* src, size_t scalars);
  void upload_reals(BufferImpl& dst, const float* src, size_t scalars);
  std::vector<double> download_reals(const BufferImpl& src, size_t scalars);

  DeviceCounters counters_;

 private:
  struct PendingRead {
    uint64_t ticket = 0;  // 0: the slot is free
    size_t bytes = 0;
    std::vector<uint8_t> data;  // the default start_read's copy
  };
  std::array<PendingRead, kMaxPendingReads> reads_;
  uint64_t next_ticket_ = 1;
};

// Checks every backend runs the same way: `b` was created by `dev`; `count` elements of `kind`
// fit one buffer of the device (else an Error with the largest count that does).
void check_owner(const DeviceApi& dev, const BufferImpl& b, std::string_view kernel);
void check_fits(const DeviceApi& dev, ElemKind kind, size_t count, std::string_view kernel,
                std::string_view what);

}  // namespace masav
