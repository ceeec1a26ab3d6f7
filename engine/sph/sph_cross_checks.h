#pragma once
// The cross-checks of the sph kernels (registry/check_catalog.cpp collects them).
#include <vector>

#include "engine/verify/kernel_check.h"

namespace masav::verify {

std::vector<KernelCheck> sph_checks();

}  // namespace masav::verify
