#pragma once
// The inputs a kernel's built-in cross-check runs on when it is checked on its own (not as part
// of a scene): those of the first scene type, in catalog order, that runs the kernel at its
// defaults, sized as `masav verify` sizes them; else generic points on a 16^3 grid. Shared by
// the Python module and the public C++ API, so both check a kernel on the same inputs.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "engine/kernels/kernel_id.h"
#include "engine/scene/scene.h"

namespace masav::verify {

struct KernelCheckInputs {
  std::string scene;  // the scene type the inputs come from, or "kernel" for the generic ones
  scene::CheckInputs in;
};

// `points` overrides the count (throws masav::Error naming `where` for 0).
KernelCheckInputs kernel_check_inputs(KernelId kernel, std::optional<uint32_t> points,
                                      uint64_t seed, std::string_view where);

}  // namespace masav::verify
