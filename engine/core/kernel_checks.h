#pragma once
// Validation shared by every backend, run before a kernel allocates or dispatches, so each
// backend rejects the same inputs with the same message.
#include <string_view>

#include "engine/core/backend.h"

namespace masav {

void check_owner(const DeviceApi& dev, const BufferImpl& b, std::string_view kernel);
void check_fits(const DeviceApi& dev, ElemKind kind, size_t count, std::string_view kernel,
                std::string_view what);
void check_grid(const GridParams& g, std::string_view kernel);

// Diagnostics a kernel reports through its flags word (the same bits on every backend).
enum DiagFlag : uint32_t {
  kDiagGatherIndexOutOfRange = 1u << 0,
  kDiagNeighborOverflow = 1u << 1,
};
// Throws the kernel's error for a non-zero flags word; `detail` is the first offending index.
void raise_diagnostics(const DeviceApi& dev, std::string_view kernel, uint32_t flags,
                       uint32_t detail, uint32_t limit);

}  // namespace masav
