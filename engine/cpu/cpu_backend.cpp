#include "engine/cpu/cpu_backend.h"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>

#include "engine/core/error.h"
#include "engine/kernels/kernel_checks.h"
#include "engine/kernels/philox.h"

namespace masav::cpu {
namespace {

std::string cpuinfo_field(const std::string& key) {
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind(key, 0) == 0) {
      auto colon = line.find(':');
      if (colon != std::string::npos) {
        auto v = line.substr(colon + 1);
        v.erase(0, v.find_first_not_of(" \t"));
        return v;
      }
    }
  }
  return "unknown";
}

}  // namespace

CpuBuffer::CpuBuffer(const DeviceApi* owner, ElemKind kind, size_t count, size_t bytes,
                     std::string label)
    : BufferImpl(owner, kind, count, bytes, std::move(label)), storage_((bytes + 7) / 8) {}

CpuBackend::CpuBackend(unsigned threads, CpuRenderPrecision render, const Tuning& tuning)
    : pool_(threads), render_(render) {
  tuning_ = tuning;
  caps_.backend = "cpu";
  caps_.device_name = cpuinfo_field("model name");
  caps_.vendor = cpuinfo_field("vendor_id");
  caps_.device_type = "cpu";
  caps_.driver = render == CpuRenderPrecision::fp64 ? "masav CPU reference (fp64)"
                                                    : "masav CPU (fp64; raymarch in fp32)";
  caps_.subgroup_size = caps_.min_subgroup_size = 1;
  caps_.max_workgroup_size = 1;
  caps_.max_workgroups_x = UINT32_MAX;
  caps_.max_buffer_bytes = 0;  // bounded by host memory only
  caps_.device_memory_bytes = uint64_t(sysconf(_SC_PHYS_PAGES)) * uint64_t(sysconf(_SC_PAGE_SIZE));
  caps_.real_is_double = true;
  caps_.threads = pool_.size();
  if (tuning.cpu.sph_precision == CpuSphPrecision::fp32) {
    const CpuSphSimd want = tuning.cpu.sph_simd;
    const SphSimd simd = want == CpuSphSimd::automatic ? best_sph_simd()
                         : want == CpuSphSimd::avx512  ? SphSimd::avx512
                         : want == CpuSphSimd::avx2    ? SphSimd::avx2
                                                       : SphSimd::generic;
    sph_simd_ = &sph_simd_kernels(simd);
    caps_.sph_pairs_fp32 = true;
    caps_.driver += fmt::format("; SPH pair kernels in fp32 ({})", sph_simd_name(simd));
  }
}

CpuBuffer& CpuBackend::own(BufferImpl& b, std::string_view kernel) {
  check_owner(*this, b, kernel);
  return static_cast<CpuBuffer&>(b);
}
const CpuBuffer& CpuBackend::own(const BufferImpl& b, std::string_view kernel) const {
  check_owner(*this, b, kernel);
  return static_cast<const CpuBuffer&>(b);
}

std::unique_ptr<BufferImpl> CpuBackend::create_buffer(ElemKind kind, size_t count,
                                                      std::string_view label) {
  const size_t bytes = count * elem_bytes(kind, real_bytes());
  try {
    return std::make_unique<CpuBuffer>(this, kind, count, bytes, std::string(label));
  } catch (const std::bad_alloc&) {
    throw Error("cpu", "create_buffer",
                fmt::format("out of host memory for '{}' ({} MiB)", label, bytes >> 20),
                "use fewer elements");
  }
}

void CpuBackend::write_bytes(BufferImpl& dst, const void* src, size_t bytes, size_t offset) {
  std::memcpy(static_cast<CpuBuffer&>(dst).data() + offset, src, bytes);
}

void CpuBackend::read_bytes(const BufferImpl& src, void* dst, size_t bytes, size_t offset) {
  std::memcpy(dst, static_cast<const CpuBuffer&>(src).data() + offset, bytes);
}

void CpuBackend::copy_buffer(const BufferImpl& src, BufferImpl& dst, size_t bytes) {
  std::memcpy(static_cast<CpuBuffer&>(dst).data(), static_cast<const CpuBuffer&>(src).data(),
              bytes);
}

void CpuBackend::fill_u32(BufferImpl& dst, uint32_t value) {
  auto& d = own(dst, "fill");
  ++counters_.fills;
  std::fill_n(d.as<uint32_t>(), d.bytes() / 4, value);
}

TimestampId CpuBackend::timestamp() {
  stamps_.push_back(std::chrono::steady_clock::now());
  return TimestampId(stamps_.size() - 1);
}

double CpuBackend::timestamp_ns(TimestampId id) {
  if (id >= stamps_.size())
    throw Error("cpu", "timestamp", fmt::format("no timestamp {}", id),
                "use an id from timestamp()");
  return std::chrono::duration<double, std::nano>(stamps_[id] - epoch_).count();
}

void CpuBackend::run_own(const KernelArgs<KernelId::radix_sort>& a) {
  auto& [p, items_, keys, values] = a;
  radix_sort_host(pool_, p.n, p.key_bits, own(keys.impl(), "radix_sort").as<uint32_t>(),
                  values ? own(values->impl(), "radix_sort").as<uint32_t>() : nullptr);
}

}  // namespace masav::cpu
