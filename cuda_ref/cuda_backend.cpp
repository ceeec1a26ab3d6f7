// CUDA backend, host side: device set-up, buffers, scratch memory, timestamps (the stream's
// launches, copies and waits: cuda_stream.cpp).
#include "cuda_ref/cuda_backend.h"

#include <fmt/format.h>

#include <algorithm>
#include <cstdlib>
#include <string_view>

#include "cuda_ref/cuda_check.h"
#include "cuda_ref/cuda_launch.h"
#include "engine/core/error.h"

namespace masav::cuda {
namespace {
constexpr uint32_t kMaxTimestamps = 4096;
}  // namespace

CudaBuffer::~CudaBuffer() {
  if (ptr_) cudaFree(ptr_);
}

DeviceScratch::~DeviceScratch() {
  if (ptr) cudaFree(ptr);
}

void* CudaBackend::scratch(const std::string& name, size_t bytes, const char* kernel) {
  DeviceScratch& s = scratch_[name];
  if (bytes <= s.bytes) return s.ptr;
  leave_capture();
  if (s.ptr) {
    ++counters_.host_syncs;  // cudaFree waits for the whole device
    check_stream(cudaFree(s.ptr), kernel, "cudaFree(scratch)");
  }
  s.ptr = nullptr;
  s.bytes = 0;
  check(cudaMalloc(&s.ptr, std::max<size_t>(bytes, 16)), kernel, "cudaMalloc(scratch)");
  s.bytes = bytes;
  return s.ptr;
}

// The automatic choices (docs/backends.md): graphs off until tools/gpu-report measures them
// faster (on an H200, 1 M particles, 64 steps: 20-30% less host CPU per step and 1% less wall
// time, but up to 17% slower at 1,024 and 32,768 particles); the wall images after the walk (64
// registers and four blocks per multiprocessor on sm_90, against 72 and three inside).
CudaBackend::CudaBackend(int device, const Tuning& tuning)
    : device_(device),
      sync_each_launch_(tuning.cuda.sync_each_launch),
      graphs_(resolve(tuning.cuda.graphs, false) && !sync_each_launch_),
      sph_images_after_(resolve(tuning.cuda.sph_images_after, true)) {
  tuning_ = tuning;
  check(cudaSetDevice(device), "init", "cudaSetDevice");
  cudaDeviceProp prop{};
  check(cudaGetDeviceProperties(&prop, device), "init", "cudaGetDeviceProperties");
  int runtime = 0, driver = 0;
  cudaRuntimeGetVersion(&runtime);
  cudaDriverGetVersion(&driver);
  caps_.backend = "cuda";
  caps_.device_name = prop.name;
  caps_.vendor = "NVIDIA";
  caps_.device_type = prop.integrated ? "integrated" : "discrete";
  caps_.driver = fmt::format("CUDA runtime {}.{}, driver {}.{}, sm_{}{}", runtime / 1000,
                             (runtime % 1000) / 10, driver / 1000, (driver % 1000) / 10, prop.major,
                             prop.minor);
  caps_.subgroup_size = caps_.min_subgroup_size = uint32_t(prop.warpSize);
  caps_.max_workgroup_size = uint32_t(prop.maxThreadsPerBlock);
  caps_.max_workgroups_x = uint32_t(prop.maxGridSize[0]);
  caps_.shared_memory_bytes = prop.sharedMemPerBlock;
  caps_.max_buffer_bytes = prop.totalGlobalMem;
  caps_.device_memory_bytes = prop.totalGlobalMem;
  caps_.timestamp_period_ns = 500.0;  // cudaEventElapsedTime resolves about 0.5 us
  caps_.real_is_double = false;
  check(cudaStreamCreateWithFlags(&stream_, cudaStreamNonBlocking), "init", "cudaStreamCreate");
  check(cudaMalloc(reinterpret_cast<void**>(&diag_), launch::kDiagWords * sizeof(uint32_t)), "init",
        "cudaMalloc(diagnostics)");
  clear_diagnostics("init");
}

CudaBackend::~CudaBackend() {
  abort_capture();
  for (cudaGraphExec_t e : graph_execs_)
    if (e) cudaGraphExecDestroy(e);
  if (stream_) cudaStreamSynchronize(stream_);
  scratch_.clear();
  for (cudaEvent_t e : events_) cudaEventDestroy(e);
  for (AsyncRead& r : async_reads_) {
    if (r.done) cudaEventDestroy(r.done);
    if (r.pinned) cudaFreeHost(r.pinned);
  }
  if (diag_) cudaFree(diag_);
  if (stream_) cudaStreamDestroy(stream_);
}

void* CudaBackend::ptr(const BufferImpl& b, const char* kernel) const {
  check_owner(*this, b, kernel);
  return static_cast<const CudaBuffer&>(b).ptr();
}

dim3 CudaBackend::grid_for(uint64_t blocks, const char* kernel) const {
  blocks = std::max<uint64_t>(blocks, 1);
  const uint64_t gx = std::min<uint64_t>(blocks, caps_.max_workgroups_x);
  const uint64_t gy = (blocks + gx - 1) / gx;
  if (gy > 65535)
    throw Error("cuda", kernel, fmt::format("{} blocks exceed the launch grid", blocks),
                "use fewer elements");
  return dim3(uint32_t(gx), uint32_t(gy), 1);
}

dim3 CudaBackend::grid_for_items(uint64_t items, const char* kernel) const {
  return grid_for((items + launch::kBlock - 1) / launch::kBlock, kernel);
}

std::unique_ptr<BufferImpl> CudaBackend::create_buffer(ElemKind kind, size_t count,
                                                       std::string_view label) {
  check_fits(*this, kind, count, "create_buffer", fmt::format("buffer '{}'", label));
  const size_t bytes = count * elem_bytes(kind, real_bytes());
  leave_capture();
  void* p = nullptr;
  const cudaError_t st = cudaMalloc(&p, std::max<size_t>(bytes, 16));
  if (st == cudaErrorMemoryAllocation) {
    (void)cudaGetLastError();
    size_t free_b = 0, total_b = 0;
    cudaMemGetInfo(&free_b, &total_b);
    throw Error("cuda", "create_buffer",
                fmt::format("out of device memory for '{}' ({} MiB; {} MiB free)", label,
                            bytes >> 20, free_b >> 20),
                "use fewer elements");
  }
  check(st, "create_buffer", "cudaMalloc");
  return std::make_unique<CudaBuffer>(this, kind, count, bytes, std::string(label), p);
}

TimestampId CudaBackend::timestamp() {
  if (events_used_ >= kMaxTimestamps)
    throw Error("cuda", "timestamp", fmt::format("more than {} timestamps", kMaxTimestamps),
                "call reset_timestamps() between measurements");
  leave_capture();
  if (events_used_ == events_.size()) {
    cudaEvent_t e;
    check(cudaEventCreate(&e), "timestamp", "cudaEventCreate");
    events_.push_back(e);
  }
  check_stream(cudaEventRecord(events_[events_used_], stream_), "timestamp", "cudaEventRecord");
  return events_used_++;
}

double CudaBackend::timestamp_ns(TimestampId id) {
  if (id >= events_used_)
    throw Error("cuda", "timestamp", fmt::format("no timestamp {}", id),
                "use an id returned by timestamp() since the last reset");
  float ms = 0;
  check_stream(cudaEventElapsedTime(&ms, events_[0], events_[id]), "timestamp",
               "cudaEventElapsedTime");
  return double(ms) * 1e6;
}

void CudaBackend::reset_timestamps() {
  events_used_ = 0;
}

}  // namespace masav::cuda
