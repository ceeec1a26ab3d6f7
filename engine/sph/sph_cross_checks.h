#pragma once
// The cross-checks of the sph kernels (registry/check_catalog.cpp collects them).
#include <vector>

#include "engine/verify/kernel_check.h"

namespace masav::verify {

std::vector<KernelCheck> sph_checks();    // with dfsph_checks()
std::vector<KernelCheck> dfsph_checks();  // engine/sph/dfsph_cross_checks.cpp

}  // namespace masav::verify
