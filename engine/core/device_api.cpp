#include "engine/core/device_api.h"

#include <fmt/format.h>

#include <cstring>

#include "engine/core/error.h"
#include "engine/core/limit_error.h"

namespace masav {
namespace {

// Reals as a backend stores them (fp32, or fp64 on the CPU reference), widened.
std::vector<double> widen_reals(const void* bytes, size_t scalars, size_t real_bytes) {
  std::vector<double> out(scalars);
  if (real_bytes == 8) {
    std::memcpy(out.data(), bytes, scalars * 8);
  } else {
    std::vector<float> narrow(scalars);
    std::memcpy(narrow.data(), bytes, scalars * 4);
    std::copy(narrow.begin(), narrow.end(), out.begin());
  }
  return out;
}

std::vector<Vec4d> as_vec4d(const std::vector<double>& flat) {
  std::vector<Vec4d> out(flat.size() / 4);
  for (size_t i = 0; i < out.size(); ++i)
    out[i] = {flat[4 * i], flat[4 * i + 1], flat[4 * i + 2], flat[4 * i + 3]};
  return out;
}

}  // namespace

void check_owner(const DeviceApi& dev, const BufferImpl& b, std::string_view kernel) {
  if (b.owner() != &dev)
    throw Error(dev.name(), std::string(kernel),
                fmt::format("buffer '{}' was created by another backend", b.label()),
                "create every buffer a kernel uses with the backend that runs it");
}

void check_fits(const DeviceApi& dev, ElemKind kind, size_t count, std::string_view kernel,
                std::string_view what) {
  const size_t eb = elem_bytes(kind, dev.real_bytes());
  const uint64_t limit = dev.caps().max_buffer_bytes;
  if (limit != 0 && uint64_t(count) * eb > limit)
    throw LimitError(
        dev.name(), std::string(kernel),
        fmt::format("{} needs {} elements of {} bytes ({} MiB), over this device's "
                    "{} MiB per buffer ({})",
                    what, count, eb, (uint64_t(count) * eb) >> 20, limit >> 20,
                    dev.caps().device_name),
        fmt::format("use at most {} elements here, or a device with larger buffers", limit / eb),
        limit);
}

void DeviceApi::check_upload(const BufferImpl& dst, size_t count) const {
  if (dst.owner() != this)
    throw Error(name(), "upload",
                fmt::format("buffer '{}' belongs to another backend", dst.label()),
                "create the buffer with the backend that uses it");
  if (count > dst.count())
    throw Error(
        name(), "upload",
        fmt::format("{} elements do not fit buffer '{}' of {}", count, dst.label(), dst.count()),
        "create a larger buffer");
}

void DeviceApi::check_range(const BufferImpl& b, size_t bytes, size_t offset,
                            const char* what) const {
  check_owner(*this, b, what);
  if (offset > b.bytes() || bytes > b.bytes() - offset)
    throw Error(name(), what,
                fmt::format("{} bytes at offset {} overrun '{}' ({} bytes)", bytes, offset,
                            b.label(), b.bytes()),
                fmt::format("{} within the buffer", what));
}

void DeviceApi::upload_bytes(BufferImpl& dst, const void* src, size_t bytes, size_t offset) {
  check_range(dst, bytes, offset, "upload");
  if (bytes) write_bytes(dst, src, bytes, offset);
  counters_.bytes_to_device += bytes;
}

void DeviceApi::download_bytes(const BufferImpl& src, void* dst, size_t bytes, size_t offset) {
  check_range(src, bytes, offset, "download");
  if (bytes) read_bytes(src, dst, bytes, offset);
  counters_.bytes_to_host += bytes;
}

uint64_t DeviceApi::read_async(const BufferImpl& src, size_t bytes, size_t offset) {
  check_range(src, bytes, offset, "asynchronous read");
  if (bytes == 0)
    throw Error(name(), "asynchronous read", fmt::format("0 bytes of '{}'", src.label()),
                "read at least one byte");
  PendingRead* free_slot = nullptr;
  for (PendingRead& r : reads_)
    if (!free_slot && r.ticket == 0) free_slot = &r;
  if (!free_slot)
    throw Error(name(), "asynchronous read",
                fmt::format("more than {} reads outstanding", kMaxPendingReads),
                "take the earlier reads first (internal error: report it)");
  const uint32_t slot = uint32_t(free_slot - reads_.data());
  start_read(slot, src, bytes, offset);
  free_slot->ticket = next_ticket_++;
  free_slot->bytes = bytes;
  counters_.bytes_to_host += bytes;
  return free_slot->ticket;
}

std::vector<uint8_t> DeviceApi::take_read(uint64_t ticket) {
  PendingRead* r = nullptr;
  for (PendingRead& p : reads_)
    if (ticket != 0 && p.ticket == ticket) r = &p;
  if (!r)
    throw Error(name(), "asynchronous read", fmt::format("no outstanding read {}", ticket),
                "take each ticket of read_async once (internal error: report it)");
  std::vector<uint8_t> out(r->bytes);
  const uint32_t slot = uint32_t(r - reads_.data());
  r->ticket = 0;  // free, whatever end_read throws
  if (end_read(slot, out.data(), out.size())) ++counters_.async_reads;
  return out;
}

void DeviceApi::discard_read(uint64_t ticket) noexcept {
  if (!ticket) return;
  try {
    (void)take_read(ticket);
  } catch (...) {
  }
}

std::vector<uint32_t> DeviceApi::take_u32s(uint64_t ticket) {
  const std::vector<uint8_t> bytes = take_read(ticket);
  std::vector<uint32_t> out(bytes.size() / 4);
  std::memcpy(out.data(), bytes.data(), out.size() * 4);
  return out;
}

std::vector<double> DeviceApi::take_reals(uint64_t ticket) {
  const std::vector<uint8_t> bytes = take_read(ticket);
  return widen_reals(bytes.data(), bytes.size() / real_bytes(), real_bytes());
}

std::vector<Vec4d> DeviceApi::take_real4s(uint64_t ticket) {
  return as_vec4d(take_reals(ticket));
}

void DeviceApi::start_read(uint32_t slot, const BufferImpl& src, size_t bytes, size_t offset) {
  reads_[slot].data.resize(bytes);
  read_bytes(src, reads_[slot].data.data(), bytes, offset);
}

bool DeviceApi::end_read(uint32_t slot, void* dst, size_t bytes) {
  std::memcpy(dst, reads_[slot].data.data(), bytes);
  return false;
}

void DeviceApi::copy_bytes(const BufferImpl& src, BufferImpl& dst, size_t bytes) {
  check_owner(*this, src, "copy");
  check_owner(*this, dst, "copy");
  if (bytes > src.bytes() || bytes > dst.bytes())
    throw Error(
        name(), "copy",
        fmt::format("{} bytes from '{}' to '{}' overrun a buffer", bytes, src.label(), dst.label()),
        "copy within both buffers");
  if (bytes) copy_buffer(src, dst, bytes);
  counters_.device_copies += bytes ? 1 : 0;
}

void DeviceApi::upload_reals(BufferImpl& dst, const double* src, size_t scalars) {
  if (real_bytes() == 8) {
    upload_bytes(dst, src, scalars * 8, 0);
    return;
  }
  std::vector<float> narrow(src, src + scalars);  // GPU backends hold fp32
  upload_bytes(dst, narrow.data(), scalars * 4, 0);
}

void DeviceApi::upload_reals(BufferImpl& dst, const float* src, size_t scalars) {
  if (real_bytes() == 4) {
    upload_bytes(dst, src, scalars * 4, 0);
    return;
  }
  std::vector<double> wide(src, src + scalars);
  upload_bytes(dst, wide.data(), scalars * 8, 0);
}

std::vector<double> DeviceApi::download_reals(const BufferImpl& src, size_t scalars) {
  std::vector<double> out(scalars);
  if (real_bytes() == 8) {
    download_bytes(src, out.data(), scalars * 8, 0);
  } else {
    std::vector<float> narrow(scalars);
    download_bytes(src, narrow.data(), scalars * 4, 0);
    std::copy(narrow.begin(), narrow.end(), out.begin());
  }
  return out;
}

void DeviceApi::upload(Buffer<uint32_t>& b, std::span<const uint32_t> v) {
  check_upload(b.impl(), v.size());
  upload_bytes(b.impl(), v.data(), v.size_bytes(), 0);
}
void DeviceApi::upload(Buffer<int32_t>& b, std::span<const int32_t> v) {
  check_upload(b.impl(), v.size());
  upload_bytes(b.impl(), v.data(), v.size_bytes(), 0);
}
void DeviceApi::upload(Buffer<float>& b, std::span<const float> v) {
  check_upload(b.impl(), v.size());
  upload_bytes(b.impl(), v.data(), v.size_bytes(), 0);
}
void DeviceApi::upload(Buffer<Real>& b, std::span<const double> v) {
  check_upload(b.impl(), v.size());
  upload_reals(b.impl(), v.data(), v.size());
}
void DeviceApi::upload(Buffer<Real>& b, std::span<const float> v) {
  check_upload(b.impl(), v.size());
  upload_reals(b.impl(), v.data(), v.size());
}
void DeviceApi::upload(Buffer<Real4>& b, std::span<const Vec4d> v) {
  static_assert(sizeof(Vec4d) == 4 * sizeof(double));
  check_upload(b.impl(), v.size());
  upload_reals(b.impl(), &v.data()->x, 4 * v.size());
}
void DeviceApi::upload(Buffer<Real4>& b, std::span<const Vec4f> v) {
  static_assert(sizeof(Vec4f) == 4 * sizeof(float));
  check_upload(b.impl(), v.size());
  upload_reals(b.impl(), &v.data()->x, 4 * v.size());
}

std::vector<uint32_t> DeviceApi::download(const Buffer<uint32_t>& b) {
  std::vector<uint32_t> out(b.size());
  download_bytes(b.impl(), out.data(), out.size() * 4, 0);
  return out;
}
std::vector<int32_t> DeviceApi::download(const Buffer<int32_t>& b) {
  std::vector<int32_t> out(b.size());
  download_bytes(b.impl(), out.data(), out.size() * 4, 0);
  return out;
}
std::vector<float> DeviceApi::download(const Buffer<float>& b) {
  std::vector<float> out(b.size());
  download_bytes(b.impl(), out.data(), out.size() * 4, 0);
  return out;
}
std::vector<double> DeviceApi::download(const Buffer<Real>& b) {
  return download_reals(b.impl(), b.size());
}
std::vector<Vec4d> DeviceApi::download(const Buffer<Real4>& b) {
  return as_vec4d(download_reals(b.impl(), 4 * b.size()));
}
std::vector<Vec4f> DeviceApi::download_f32(const Buffer<Real4>& b) {
  std::vector<double> flat = download_reals(b.impl(), 4 * b.size());
  std::vector<Vec4f> out(b.size());
  for (size_t i = 0; i < b.size(); ++i)
    out[i] = {float(flat[4 * i]), float(flat[4 * i + 1]), float(flat[4 * i + 2]),
              float(flat[4 * i + 3])};
  return out;
}

CaptureScope::CaptureScope(DeviceApi& d) : d_(d) {
  d_.begin_capture();
}

CaptureScope::~CaptureScope() {
  if (open_) d_.abort_capture();
}

void CaptureScope::commit() {
  open_ = false;
  d_.end_capture();
}

}  // namespace masav
