#pragma once
// The cross-checks of the random, sort and hash-grid kernels (registry/check_catalog.cpp
// collects them).
#include <vector>

#include "engine/verify/kernel_check.h"

namespace masav::verify {

std::vector<KernelCheck> foundation_checks();

}  // namespace masav::verify
