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

// Throws the kernel's error for a non-zero flags word (kDiag* in engine/kernels/grid_params.h);
// `detail` is the first offending index.
void raise_diagnostics(const DeviceApi& dev, std::string_view kernel, uint32_t flags,
                       uint32_t detail, uint32_t limit);

}  // namespace masav
