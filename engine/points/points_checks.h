#pragma once
// The cross-checks of the points kernels (registry/check_catalog.cpp collects them).
#include <vector>

#include "engine/verify/kernel_check.h"

namespace masav::verify {

std::vector<KernelCheck> points_checks();

}  // namespace masav::verify
