#include "engine/kernels/backend.h"

#include <fmt/format.h>

#include <cstring>

#include "engine/core/error.h"
#include "engine/kernels/kernel_checks.h"

namespace masav {

void Backend::check_buffers(KernelId id, std::span<const BufferImpl* const> impls,
                            std::span<const char* const> names,
                            std::span<const bool> required) const {
  const std::string kernel(kernel_name(id));
  for (size_t i = 0; i < impls.size(); ++i) {
    if (!impls[i]) {
      if (!required[i]) continue;
      throw Error(name(), kernel, fmt::format("buffer '{}' is empty (never created)", names[i]),
                  "create every buffer a kernel uses with the backend that runs it");
    }
    check_owner(*this, *impls[i], kernel);
  }
}

std::vector<KernelTiming> Backend::take_kernel_timings() {
  std::vector<KernelTiming> out;
  out.swap(timings_);
  return out;
}

void Backend::perturb(BufferImpl* out) {
  if (!out || out->count() == 0) return;
  // The middle scalar of the buffer: 32-bit words get their lowest bit flipped, reals move by
  // 1e-3 relative (to 1 from 0), enough for any stated tolerance to catch.
  const size_t scalar_bytes =
      out->kind() == ElemKind::real || out->kind() == ElemKind::real4 ? real_bytes() : 4;
  const size_t offset = out->bytes() / scalar_bytes / 2 * scalar_bytes;
  if (scalar_bytes == 8) {
    double v = 0;
    download_bytes(*out, &v, 8, offset);
    v = v == 0 ? 1.0 : v * (1.0 + 1e-3);
    upload_bytes(*out, &v, 8, offset);
  } else if (out->kind() == ElemKind::u32 || out->kind() == ElemKind::i32) {
    uint32_t w = 0;
    download_bytes(*out, &w, 4, offset);
    w ^= 1u;
    upload_bytes(*out, &w, 4, offset);
  } else {
    float v = 0;
    download_bytes(*out, &v, 4, offset);
    v = v == 0 ? 1.0f : v * (1.0f + 1e-3f);
    upload_bytes(*out, &v, 4, offset);
  }
}

}  // namespace masav
