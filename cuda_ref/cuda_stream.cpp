// CUDA backend, host side: what is queued on the stream and where the host waits for it. Every
// launch, copy and memset is ordered on stream_ (a non-blocking stream, so nothing may go to the
// legacy default stream); the host waits only for downloads, finish() and the asynchronous
// reads it takes (each for its own event, with later work still queued). Each is counted in
// counters_, and a fault CUDA reports late is traced to the last kernel launched.
#include <fmt/format.h>

#include <cstring>

#include "cuda_ref/cuda_backend.h"
#include "cuda_ref/cuda_check.h"
#include "cuda_ref/cuda_launch.h"
#include "engine/kernels/kernel_checks.h"

namespace masav::cuda {
namespace {

constexpr uint32_t kCleanDiagnostics[launch::kDiagWords] = {0, 0, UINT32_MAX, 0};

std::string launch_name(const char* kernel, const char* step) {
  return step ? fmt::format("{} ({})", kernel, step) : std::string(kernel);
}

}  // namespace

void CudaBackend::launched(cudaError_t status, const char* kernel, const char* step) {
  // Checked before the record moves on: a fault reported here is an earlier kernel's.
  if (status != cudaSuccess) check_stream(status, launch_name(kernel, step).c_str(), "launch");
  ++counters_.launches;
  last_kernel_ = kernel;
  last_step_ = step;
  if (!sync_each_launch_) return;
  ++counters_.host_syncs;
  const cudaError_t ran = cudaStreamSynchronize(stream_);
  if (is_kernel_fault(ran)) throw_fault_of(ran, last_launch());
  check(ran, kernel, "cudaStreamSynchronize (cuda.sync_each_launch)");
}

void CudaBackend::check_stream(cudaError_t status, const char* where, const char* what) const {
  if (last_kernel_ && is_kernel_fault(status))
    throw_kernel_fault(status, fmt::format("{} in {}", what, where), last_launch());
  check(status, where, what);
}

std::string CudaBackend::last_launch() const {
  return launch_name(last_kernel_, last_step_);
}

void CudaBackend::wait(const char* where) {
  leave_capture();
  ++counters_.host_syncs;
  check_stream(cudaStreamSynchronize(stream_), where, "cudaStreamSynchronize");
}

void CudaBackend::zero(void* dst, size_t bytes, const char* kernel) {
  set_bytes(dst, 0, bytes, kernel);
}

void CudaBackend::set_bytes(void* dst, int byte, size_t bytes, const char* kernel) {
  ++counters_.fills;
  check_stream(cudaMemsetAsync(dst, byte, bytes, stream_), kernel, "cudaMemsetAsync");
}

void CudaBackend::copy_device(void* dst, const void* src, size_t bytes, const char* kernel) {
  ++counters_.device_copies;
  check_stream(cudaMemcpyAsync(dst, src, bytes, cudaMemcpyDeviceToDevice, stream_), kernel,
               "cudaMemcpyAsync");
}

void CudaBackend::clear_diagnostics(const char* where) {
  leave_capture();  // a copy from pageable memory
  // From static memory: a pageable source is staged before the call returns.
  check_stream(cudaMemcpyAsync(diag_, kCleanDiagnostics, sizeof kCleanDiagnostics,
                               cudaMemcpyHostToDevice, stream_),
               where, "cudaMemcpyAsync(diagnostics)");
}

void CudaBackend::write_bytes(BufferImpl& dst, const void* src, size_t bytes, size_t offset) {
  leave_capture();
  // From pageable memory the call returns once `src` has been staged.
  check_stream(cudaMemcpyAsync(static_cast<char*>(ptr(dst, "upload")) + offset, src, bytes,
                               cudaMemcpyHostToDevice, stream_),
               "upload", "cudaMemcpyAsync");
}

void CudaBackend::read_bytes(const BufferImpl& src, void* dst, size_t bytes, size_t offset) {
  leave_capture();
  // Into pageable memory the copy returns once done, after the work queued before it; with
  // settle's wait that is one host sync.
  check_stream(cudaMemcpyAsync(dst, static_cast<const char*>(ptr(src, "download")) + offset, bytes,
                               cudaMemcpyDeviceToHost, stream_),
               "download", "cudaMemcpyAsync");
  settle("download");
}

uint64_t CudaBackend::work_count() const {
  return counters_.launches + counters_.fills + counters_.device_copies + counters_.bytes_to_device;
}

void CudaBackend::start_read(uint32_t slot, const BufferImpl& src, size_t bytes, size_t offset) {
  leave_capture();
  AsyncRead& r = async_reads_[slot];
  constexpr size_t kDiagBytes = launch::kDiagWords * sizeof(uint32_t);
  const size_t room = (bytes + 15) / 16 * 16;  // the diagnostics words after the bytes, aligned
  if (r.bytes < room) {
    // The slot is free: no copy still writes its memory (its read was taken, with its event).
    if (r.pinned) check(cudaFreeHost(r.pinned), "asynchronous read", "cudaFreeHost");
    r.pinned = nullptr;
    r.bytes = 0;
    check(cudaMallocHost(&r.pinned, room + kDiagBytes), "asynchronous read", "cudaMallocHost");
    r.bytes = room;
  }
  // A blocking-sync event: the host sleeps while it waits for a read instead of spinning (CUDA's
  // default on a machine with more cores than contexts), so a simulation that runs blocks
  // ahead of the device leaves the host's core to the rest of the program (a renderer, a UI).
  if (!r.done)
    check(cudaEventCreateWithFlags(&r.done, cudaEventDisableTiming | cudaEventBlockingSync),
          "asynchronous read", "cudaEventCreate");
  auto* host = static_cast<char*>(r.pinned);
  const char* from = static_cast<const char*>(ptr(src, "asynchronous read")) + offset;
  check_stream(cudaMemcpyAsync(host, from, bytes, cudaMemcpyDeviceToHost, stream_),
               "asynchronous read", "cudaMemcpyAsync");
  check_stream(cudaMemcpyAsync(host + r.bytes, diag_, kDiagBytes, cudaMemcpyDeviceToHost, stream_),
               "asynchronous read", "cudaMemcpyAsync(diagnostics)");
  check_stream(cudaEventRecord(r.done, stream_), "asynchronous read", "cudaEventRecord");
  r.work_mark = work_count();
}

bool CudaBackend::end_read(uint32_t slot, void* dst, size_t bytes) {
  leave_capture();
  AsyncRead& r = async_reads_[slot];
  // Counted as DeviceApi::take_read says: with later work queued an asynchronous read, else a
  // host sync where it has to wait (nothing, where the copy is done already).
  const cudaError_t ready = cudaEventQuery(r.done);
  const bool waits = ready == cudaErrorNotReady;
  if (!waits) check_stream(ready, "asynchronous read", "cudaEventQuery");
  const bool later_work = work_count() != r.work_mark;
  if (waits && !later_work) ++counters_.host_syncs;
  if (waits)
    check_stream(cudaEventSynchronize(r.done), "asynchronous read", "cudaEventSynchronize");
  const auto* host = static_cast<const char*>(r.pinned);
  std::memcpy(dst, host, bytes);
  uint32_t d[launch::kDiagWords];
  std::memcpy(d, host + r.bytes, sizeof d);
  if (d[1] != 0) {
    clear_diagnostics("asynchronous read");
    raise_diagnostics(*this, d[1], d[2], pending_diag_limit_);
  }
  return later_work;
}

void CudaBackend::copy_buffer(const BufferImpl& src, BufferImpl& dst, size_t bytes) {
  // DeviceApi::copy_bytes counts it.
  check_stream(
      cudaMemcpyAsync(ptr(dst, "copy"), ptr(src, "copy"), bytes, cudaMemcpyDeviceToDevice, stream_),
      "copy", "cudaMemcpyAsync");
}

void CudaBackend::fill_u32(BufferImpl& dst, uint32_t value) {
  const size_t words = dst.bytes() / 4;
  if (!words) return;
  const uint32_t byte = value & 0xFFu;
  if (value == byte * 0x01010101u) {
    // A word of four equal bytes (0, ~0: the stats' reset) is a memset, not a launch.
    set_bytes(ptr(dst, "fill"), int(byte), words * 4, "fill");
    return;
  }
  ++counters_.fills;  // a kernel (cudaMemsetAsync sets bytes, not words): a fill and a launch
  launched(launch::fill_u32(stream_, grid_for_items(words, "fill"),
                            static_cast<uint32_t*>(ptr(dst, "fill")), words, value),
           "fill");
}

void CudaBackend::finish() {
  settle("finish");
}

void CudaBackend::settle(const char* where) {
  leave_capture();
  // Queued behind the work, so that one wait covers the work and the diagnostics' read.
  uint32_t d[launch::kDiagWords];
  check_stream(cudaMemcpyAsync(d, diag_, sizeof d, cudaMemcpyDeviceToHost, stream_), where,
               "cudaMemcpyAsync(diagnostics)");
  wait(where);
  if (d[1] == 0) return;
  clear_diagnostics(where);
  raise_diagnostics(*this, d[1], d[2], pending_diag_limit_);
}

}  // namespace masav::cuda
