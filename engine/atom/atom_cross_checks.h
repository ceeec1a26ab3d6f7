#pragma once
// The cross-checks of the atom kernels (registry/check_catalog.cpp collects them).
#include <vector>

#include "engine/verify/kernel_check.h"

namespace masav::verify {

std::vector<KernelCheck> atom_checks();

}  // namespace masav::verify
